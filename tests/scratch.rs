mod common;
use hysteresis::bwbn::*;
use hysteresis::Element;

fn params(set: EffectSet, extra: &[(&str, f64)]) -> BwbnParams<f64> {
    BwbnParams::from_named(set, |n| {
        extra
            .iter()
            .find(|(k, _)| *k == n)
            .map(|(_, v)| *v)
            .or(match n {
                "k0" => Some(6.0),
                "alpha" => Some(0.2),
                "n" => Some(1.2),
                "beta" => Some(2.0),
                "gamma" => Some(-1.0),
                _ => None,
            })
    })
    .unwrap()
}
fn run(p: BwbnParams<f64>, ctl: Control<f64>, h: &[f64]) -> Vec<f64> {
    let mut el = Bwbn::with_extra(p, (), ctl);
    h.iter()
        .map(|&u| {
            let r = el.set_trial(u).unwrap_or_else(|e| panic!("{e} at {u}"));
            el.commit();
            r.force
        })
        .collect()
}
fn full() -> BwbnParams<f64> {
    params(
        EffectSet::BWBN,
        &[
            ("zeta0", 0.9),
            ("p", 0.01),
            ("q", 0.1),
            ("psi0", 0.2),
            ("delta_psi", 5e-4),
            ("lambda", 0.5),
            ("delta_A", 2e-4),
            ("delta_nu", 5e-4),
            ("delta_eta", 5e-4),
            ("energy_limit", 4000.0),
        ],
    )
}

#[test]
fn acc() {
    let h = common::reference_history();
    for (name, p) in [("plain", params(EffectSet::NONE, &[])), ("full", full())] {
        let refv = run(
            p,
            Control {
                method: Method::Dp54,
                tol: 1e-12,
                max_substeps: 60000,
            },
            &h,
        );
        let peak = refv.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        for (m, tol) in [
            (Method::Dp54, 1e-7),
            (Method::Dp54, 1e-8),
            (Method::Dp54, 1e-9),
            (Method::Bs32, 1e-5),
            (Method::Bs32, 1e-6),
        ] {
            let v = run(
                p,
                Control {
                    method: m,
                    tol,
                    max_substeps: 64,
                },
                &h,
            );
            let d = v
                .iter()
                .zip(&refv)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            println!("{name} {m:?} tol {tol:e} maxerr {:e}", d / peak);
        }
    }
}

#[test]
fn speed() {
    let h = common::reference_history();
    for (name, p) in [("plain", params(EffectSet::NONE, &[])), ("full", full())] {
        for (m, tol) in [
            (Method::Dp54, 1e-8),
            (Method::Dp54, 1e-9),
            (Method::Bs32, 1e-6),
        ] {
            let t0 = std::time::Instant::now();
            let mut n = 0;
            for _ in 0..50 {
                let v = run(
                    p,
                    Control {
                        method: m,
                        tol,
                        max_substeps: 64,
                    },
                    &h,
                );
                n += v.len();
                std::hint::black_box(v);
            }
            let dt = t0.elapsed().as_secs_f64();
            println!("{name} {m:?} {tol:e}: {:.1} ns/step", dt / n as f64 * 1e9);
        }
    }
}

#[test]
fn tangent_probe() {
    let h = common::reference_history();
    for tol in [1e-9, 1e-12] {
        let mut el = Bwbn::with_extra(
            params(EffectSet::NONE, &[]),
            (),
            Control {
                method: Method::Dp54,
                tol,
                max_substeps: 60000,
            },
        );
        for &u in &h[..671] {
            el.set_trial(u).unwrap();
            el.commit();
        }
        let u = h[671];
        let r = el.set_trial(u).unwrap();
        print!(
            "tol {tol:e} z_c {:e} tangent {} ",
            el.committed().z,
            r.tangent
        );
        for d in [1e-3, 1e-4, 1e-5, 1e-6, 1e-7] {
            let fp = el.set_trial(u + d).unwrap().force;
            let fm = el.set_trial(u - d).unwrap().force;
            print!(" d={d:e}: {}", (fp - fm) / (2.0 * d));
        }
        el.set_trial(u).unwrap();
        println!(" z_t {:e}", el.trial().z);
    }
}
