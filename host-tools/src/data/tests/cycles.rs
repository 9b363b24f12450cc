//! Reversals, cycles, branches and energies against histories whose structure
//! is known independently.

use super::data_dir;
use crate::data::{
    read, Branch, Cycles, Direction, Label, Protocol, ReadOptions, SegmentOptions, Segmentation,
    Threshold,
};
use std::f64::consts::PI;

#[test]
fn clean_triangular_history_reverses_at_every_peak() {
    // 18 cycles of 200 steps from 0: +A at step 50, -A at step 150 of each.
    let u = Protocol::opensees_reference().generate().unwrap();
    let c = Cycles::find(&u, Threshold::default()).unwrap();
    let expected: Vec<usize> = (0..18)
        .flat_map(|k| [200 * k + 50, 200 * k + 150])
        .collect();
    assert_eq!(c.reversals(), expected.as_slice());
    assert_eq!(c.half_cycles().len(), 37);
    assert_eq!(c.cycles().len(), 19);
    assert_eq!(c.complete_cycles(), 18);
    let last = c.cycles().last().unwrap();
    assert!(!last.complete);
    assert_eq!((last.from, last.to), (3550, 3600));
    // Peaks per half-cycle: the protocol's amplitudes, alternating in sign.
    let amps = [0.5, 1.0, 2.0, 4.0, 6.0, 8.0];
    for h in &c.half_cycles()[..36] {
        let a = amps[h.index / 6];
        let (sign, dir) = if h.index % 2 == 0 {
            (1.0, Direction::Increasing)
        } else {
            (-1.0, Direction::Decreasing)
        };
        assert_eq!(u[h.to], sign * a, "half-cycle {}", h.index);
        assert_eq!(h.direction, dir);
        assert!(h.complete);
    }
    // Every sample is owned by exactly one half-cycle, in order.
    let owner = c.half_cycle_of_samples();
    assert_eq!(owner.len(), u.len());
    assert!(owner.windows(2).all(|w| w[1] == w[0] || w[1] == w[0] + 1));
    assert_eq!(owner[50], 0);
    assert_eq!(owner[51], 1);
}

/// The synthetic records were made with a triangular protocol: two cycles at
/// each of 5, 10, 20, 30, 40, 60, 80, 100 mm, 100 samples a cycle, peaks at
/// samples 25 + 50 k. This structure was read off the files independently
/// (local extrema of a 5-point moving average, and the largest |u| of each
/// 100-sample block, in a Python session), not from this code.
#[test]
fn noisy_synthetic_records_have_the_protocol_cycles() {
    let amps = [5.0, 10.0, 20.0, 30.0, 40.0, 60.0, 80.0, 100.0];
    for name in ["s1_hidden_pinching.csv", "s2_hidden_degradation.csv"] {
        let r = read(
            data_dir().join("synthetic").join(name),
            &ReadOptions::default(),
        )
        .unwrap();
        let u = r.displacement().unwrap();
        let c = r.cycles(Threshold::default()).unwrap();
        assert!(
            (c.threshold() - 2.0).abs() < 0.01,
            "{name}: {}",
            c.threshold()
        );
        assert_eq!(c.reversals().len(), 32, "{name}");
        assert_eq!(c.complete_cycles(), 16, "{name}");
        for (k, &i) in c.reversals().iter().enumerate() {
            let nominal = 25 + 50 * k;
            // Noise sd 0.2 mm against a ramp of 4 A / 100 per sample: the
            // largest sample sits within a few samples of the true peak.
            assert!(i.abs_diff(nominal) <= 3, "{name}: reversal {k} at {i}");
            let target = if k % 2 == 0 { 1.0 } else { -1.0 } * amps[k / 4];
            assert!(
                (u[i] - target).abs() < 1.0,
                "{name}: reversal {k}: {} vs {target}",
                u[i]
            );
        }
        // The count does not depend on the threshold from 0.8 mm (4 noise sd)
        // to 4 mm (the first excursion, from rest, is only 5 mm) ...
        for f in [0.004, 0.01, 0.02] {
            let c = r.cycles(Threshold::FractionOfRange(f)).unwrap();
            assert_eq!(c.reversals().len(), 32, "{name}: {f}");
        }
        // ... above the 10 mm swing of the 5 mm cycles, those vanish ...
        let c = r.cycles(Threshold::Absolute(12.0)).unwrap();
        assert!(c.reversals().len() < 32, "{name}");
        // ... but noise makes spurious reversals without one.
        let c = r.cycles(Threshold::Absolute(0.0)).unwrap();
        assert!(c.reversals().len() > 100, "{}", c.reversals().len());
    }
}

#[test]
fn short_and_flat_signals() {
    let c = Cycles::find(&[], Threshold::default()).unwrap();
    assert!(c.half_cycles().is_empty() && c.cycles().is_empty());
    let c = Cycles::find(&[3.0], Threshold::default()).unwrap();
    assert_eq!(c.half_cycles().len(), 1);
    assert_eq!(c.half_cycles()[0].samples(), 0..1);
    // Wiggles below the threshold are one half-cycle.
    let c = Cycles::find(&[0.0, 0.1, -0.1, 0.05, 1.0], Threshold::Absolute(0.5)).unwrap();
    assert!(c.reversals().is_empty());
    assert_eq!(c.half_cycles().len(), 1);
    assert!(Cycles::find(&[0.0, f64::NAN], Threshold::default()).is_err());
    assert!(Cycles::find(&[0.0, 1.0], Threshold::Absolute(-1.0)).is_err());
    assert!(Cycles::find(&[0.0, 1.0], Threshold::FractionOfRange(f64::NAN)).is_err());
}

#[test]
fn branch_classes_of_a_hand_made_record() {
    // u: 0 -> 4 -> -4 -> 6 -> 2 (a larger positive excursion, then a partial
    // unloading). F: a hand-drawn pinched loop; zero crossings between samples.
    let u = [
        0.0, 2.0, 4.0, // virgin push, peak at 2
        3.0, 1.0, -1.0, -3.0, -4.0, // pull: F crosses zero between 3 and 4, beyond 0 at 5
        -2.0, 0.0, 2.0, 4.0, 5.0,
        6.0, // push: F crosses zero between 8 and 9, new peak after 4
        4.0, 2.0, // partial unloading
    ];
    let f = [
        0.0, 8.0, 10.0, //
        6.0, -0.5, -3.0, -7.0, -10.0, //
        -4.0, 0.5, 1.5, 9.0, 11.0, 12.0, //
        7.0, 2.0,
    ];
    let options = SegmentOptions {
        threshold: Threshold::Absolute(1.0),
        near_zero_fraction: 0.2,
    };
    let s = Segmentation::new(&u, &f, &u, &options).unwrap();
    assert_eq!(s.cycles().reversals(), &[2, 7, 13]);
    use Branch::{Loading as L, Reloading as R, Unloading as U};
    let expected = [
        // half-cycle 0: virgin loading
        (0, L),
        (0, L),
        (0, L),
        // half-cycle 1 (decreasing): unloading while F > 0, reloading inside
        // the envelope (u >= 0, the smallest u before), loading below it.
        (1, U),
        (1, R),
        (1, L),
        (1, L),
        (1, L),
        // half-cycle 2 (increasing): unloading while F < 0, reloading up to
        // u = 4 (the largest u before), loading beyond.
        (2, U),
        (2, R),
        (2, R),
        (2, R),
        (2, L),
        (2, L),
        // half-cycle 3: unloading, F still positive.
        (3, U),
        (3, U),
    ];
    // Near zero: |F| < 0.2 * 10 in cycle 0 (samples 0..=7), < 0.2 * 12 in cycle 1.
    let near = [0, 4, 9, 10, 15];
    for (i, (l, (h, b))) in s.labels().iter().zip(expected).enumerate() {
        let want = Label {
            half_cycle: h,
            cycle: h / 2,
            branch: b,
            near_zero_force: near.contains(&i),
        };
        assert_eq!(*l, want, "sample {i}");
    }
    // Peak force per half-cycle, in its direction (the last, decreasing
    // half-cycle's is its smallest force).
    let peaks: Vec<(usize, f64)> = s.peak_forces().iter().map(|p| (p.index, p.value)).collect();
    assert_eq!(peaks, [(2, 10.0), (7, -10.0), (13, 12.0), (15, 2.0)]);
}

#[test]
fn energy_of_a_rectangle_is_exact() {
    // Rigid-plastic loop: F = +P on the way up, -P on the way down, between
    // -A and +A; each jump is two samples at the same u. Area 2A x 2P.
    let (a, p) = (3.0, 2.5);
    let mut u = vec![0.0];
    let mut f = vec![p];
    for k in 1..=3 {
        u.push(a * k as f64 / 3.0);
        f.push(p);
    }
    for _ in 0..2 {
        u.push(a);
        f.push(-p);
        for k in 1..=6 {
            u.push(a - 2.0 * a * k as f64 / 6.0);
            f.push(-p);
        }
        u.push(-a);
        f.push(p);
        for k in 1..=6 {
            u.push(-a + 2.0 * a * k as f64 / 6.0);
            f.push(p);
        }
    }
    let s = Segmentation::new(&u, &f, &u, &SegmentOptions::default()).unwrap();
    let c = s.cycles();
    assert_eq!(c.reversals().len(), 4);
    // Cycle 1 runs from the first -A to the second -A: one full rectangle.
    assert_eq!(s.energy()[1], 4.0 * a * p);
    // Cycle 0 runs from 0 up to +A and down to -A: P*A + P*2A.
    assert_eq!(s.energy()[0], 3.0 * a * p);
    // Energies add up to the work over the whole record.
    let total: f64 = (0..u.len() - 1)
        .map(|i| 0.5 * (f[i] + f[i + 1]) * (u[i + 1] - u[i]))
        .sum();
    assert!((s.energy().iter().sum::<f64>() - total).abs() < 1e-12);
}

#[test]
fn energy_of_an_ellipse_converges_to_pi_a_b_sin_phi() {
    // u = A sin(theta), F = B sin(theta + phi): the loop area is pi A B sin(phi);
    // from theta = 0 to 3 pi / 2 the work is A B (cos(phi) / 2 + 3 pi sin(phi) / 4).
    let (a, b, phi) = (5.0, 40.0, 0.4f64);
    let exact = PI * a * b * phi.sin();
    let first = a * b * (0.5 * phi.cos() + 0.75 * PI * phi.sin());
    let mut errors = Vec::new();
    for n in [64, 256, 1024] {
        let theta: Vec<f64> = (0..=3 * n)
            .map(|k| 2.0 * PI * k as f64 / n as f64)
            .collect();
        let u: Vec<f64> = theta.iter().map(|t| a * t.sin()).collect();
        let f: Vec<f64> = theta.iter().map(|t| b * (t + phi).sin()).collect();
        let s = Segmentation::new(&u, &f, &u, &SegmentOptions::default()).unwrap();
        let c = s.cycles();
        // Reversals at theta = pi/2 + k pi, exactly on samples (n is a multiple of 4).
        let expected: Vec<usize> = (0..6).map(|k| n / 4 + k * n / 2).collect();
        assert_eq!(c.reversals(), expected.as_slice());
        assert!(c.cycles()[1].complete);
        errors.push(((s.energy()[1] - exact) / exact).abs());
        assert!(((s.energy()[0] - first) / first).abs() < 2.0 * (2.0 * PI / n as f64).powi(2));
    }
    // Trapezoidal rule: second order in the step.
    assert!(errors[2] < 1e-4, "{errors:?}");
    assert!(
        errors[0] / errors[1] > 15.0 && errors[1] / errors[2] > 15.0,
        "{errors:?}"
    );
}

#[test]
fn residual_breakdown_partitions_the_total() {
    let r = read(
        data_dir().join("synthetic/s1_hidden_pinching.csv"),
        &ReadOptions::default(),
    )
    .unwrap();
    let s = r.segment(&SegmentOptions::default()).unwrap();
    let f = r.force().unwrap();
    // A residual that differs by sample.
    let res: Vec<f64> = f
        .iter()
        .enumerate()
        .map(|(i, v)| 0.01 * v + (i % 7) as f64)
        .collect();
    let b = s.breakdown(&res).unwrap();
    let total: f64 = res.iter().map(|x| x * x).sum();
    assert!((b.total.sum_sq - total).abs() < 1e-9 * total);
    assert_eq!(b.total.count, f.len());
    let sum = |t: &[crate::data::Tally]| {
        (
            t.iter().map(|t| t.count).sum::<usize>(),
            t.iter().map(|t| t.sum_sq).sum::<f64>(),
        )
    };
    for (count, sq) in [
        sum(&b.by_cycle),
        sum(&b.by_half_cycle),
        sum(&b.by_branch_zone.concat()),
    ] {
        assert_eq!(count, f.len());
        assert!((sq - total).abs() < 1e-9 * total);
    }
    // Cycle by cycle, the tally is over the cycle's own samples.
    let c = &s.cycles().cycles()[5];
    let own: f64 = res[c.samples()].iter().map(|x| x * x).sum();
    assert_eq!(b.by_cycle[5].count, c.samples().len());
    assert!((b.by_cycle[5].sum_sq - own).abs() < 1e-9 * own);
    // Every branch class occurs in a cyclic test, and so does the pinched zone.
    for br in Branch::ALL {
        assert!(b.branch(br).count > 50, "{br}: {}", b.branch(br).count);
    }
    assert!(b.zone(true).count > 50);
    assert!(s.breakdown(&res[1..]).is_err());
}

#[test]
fn synthetic_peak_forces_and_energies_grow_with_amplitude() {
    // A physical check of the pieces together: in a test of increasing
    // amplitude the energy of the first cycle at each amplitude grows, every
    // complete cycle dissipates (positive area), and peak forces alternate in
    // sign with the half-cycles.
    for name in ["s1_hidden_pinching.csv", "s2_hidden_degradation.csv"] {
        let r = read(
            data_dir().join("synthetic").join(name),
            &ReadOptions::default(),
        )
        .unwrap();
        let s = r.segment(&SegmentOptions::default()).unwrap();
        let e = s.energy();
        assert_eq!(e.len(), 17);
        assert!(e[..16].iter().all(|&x| x > 0.0), "{name}: {e:?}");
        for k in (2..16).step_by(2) {
            assert!(e[k] > e[k - 2], "{name}: cycle {k}: {e:?}");
        }
        for (h, p) in s.cycles().half_cycles().iter().zip(s.peak_forces()) {
            assert_eq!(
                p.value > 0.0,
                h.direction == Direction::Increasing,
                "{name}"
            );
        }
    }
}
