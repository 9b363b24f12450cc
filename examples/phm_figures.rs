//! Figures and numbers of `docs/phm.md`:
//!
//! * `docs/phm-rules.svg`: the rule paths of the PHM on a constructed twist
//!   history, with the control points of every rule branch marked;
//! * `docs/phm-vs-<case>.svg`: the PHM against OpenSees' `Hysteretic` and
//!   `Pinching4` reference cases (same primary curve), and a Markdown table
//!   of the differences on standard output.
//!
//! Run from the repository root: `cargo run --example phm_figures`.

use hysteresis::phm::{Branch, Coefficients, Direction, Kind, Phm, PhmParams};
use hysteresis::Element;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn read_csv(path: &Path) -> Vec<Vec<f64>> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    text.lines()
        .enumerate()
        .skip(1)
        .filter(|(_, l)| !l.trim().is_empty())
        .map(|(i, l)| {
            l.split(',')
                .enumerate()
                .map(|(j, v)| {
                    let v = v.trim();
                    if v == "nan" {
                        return f64::NAN;
                    }
                    v.parse().unwrap_or_else(|e| {
                        panic!(
                            "{}:{}:{}: expected a number, got {v:?}: {e}",
                            path.display(),
                            i + 1,
                            j + 1
                        )
                    })
                })
                .collect()
        })
        .collect()
}

/// One line series of a plot.
struct Series {
    label: String,
    color: &'static str,
    dashed: bool,
    points: Vec<(f64, f64)>,
}

/// A minimal x-y line plot written as SVG.
struct Plot {
    title: String,
    xlabel: &'static str,
    ylabel: &'static str,
    series: Vec<Series>,
    markers: Vec<Marker>,
}

fn ticks(lo: f64, hi: f64) -> Vec<f64> {
    let span = hi - lo;
    let raw = span / 8.0;
    let mag = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|s| *s >= raw)
        .unwrap_or(10.0 * mag);
    let mut t = (lo / step).ceil() * step;
    let mut out = Vec::new();
    while t <= hi + 1e-9 {
        out.push(if t.abs() < 1e-12 { 0.0 } else { t });
        t += step;
    }
    out
}

impl Plot {
    fn write(&self, path: &Path) {
        let (w, h, ml, mr, mt, mb) = (760.0, 560.0, 70.0, 20.0, 40.0, 60.0);
        let all = self.series.iter().flat_map(|s| s.points.iter().copied());
        let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for (x, y) in all.chain(self.markers.iter().map(|m| (m.0, m.1))) {
            x0 = x0.min(x);
            x1 = x1.max(x);
            y0 = y0.min(y);
            y1 = y1.max(y);
        }
        let (px, py) = (0.05 * (x1 - x0), 0.08 * (y1 - y0));
        let (x0, x1, y0, y1) = (x0 - px, x1 + px, y0 - py, y1 + py);
        let sx = |x: f64| ml + (x - x0) / (x1 - x0) * (w - ml - mr);
        let sy = |y: f64| mt + (y1 - y) / (y1 - y0) * (h - mt - mb);
        let mut s = String::new();
        let _ = writeln!(
            s,
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="sans-serif" font-size="12">"#
        );
        let _ = writeln!(s, r#"<rect width="{w}" height="{h}" fill="white"/>"#);
        let _ = writeln!(
            s,
            r#"<text x="{}" y="22" text-anchor="middle" font-size="15">{}</text>"#,
            w / 2.0,
            self.title
        );
        for t in ticks(x0, x1) {
            let x = sx(t);
            let _ = writeln!(
                s,
                r##"<line x1="{x:.1}" y1="{mt}" x2="{x:.1}" y2="{:.1}" stroke="#eee"/><text x="{x:.1}" y="{:.1}" text-anchor="middle">{t}</text>"##,
                h - mb,
                h - mb + 16.0
            );
        }
        for t in ticks(y0, y1) {
            let y = sy(t);
            let _ = writeln!(
                s,
                r##"<line x1="{ml}" y1="{y:.1}" x2="{:.1}" y2="{y:.1}" stroke="#eee"/><text x="{:.1}" y="{:.1}" text-anchor="end">{t}</text>"##,
                w - mr,
                ml - 6.0,
                y + 4.0
            );
        }
        let _ = writeln!(
            s,
            r##"<line x1="{:.1}" y1="{mt}" x2="{:.1}" y2="{:.1}" stroke="#999"/><line x1="{ml}" y1="{:.1}" x2="{:.1}" y2="{:.1}" stroke="#999"/>"##,
            sx(0.0),
            sx(0.0),
            h - mb,
            sy(0.0),
            w - mr,
            sy(0.0)
        );
        let _ = writeln!(
            s,
            r#"<text x="{:.1}" y="{:.1}" text-anchor="middle">{}</text><text x="16" y="{:.1}" text-anchor="middle" transform="rotate(-90 16 {:.1})">{}</text>"#,
            (ml + w - mr) / 2.0,
            h - 18.0,
            self.xlabel,
            (mt + h - mb) / 2.0,
            (mt + h - mb) / 2.0,
            self.ylabel
        );
        for (i, ser) in self.series.iter().enumerate() {
            let pts: Vec<String> = ser
                .points
                .iter()
                .map(|&(x, y)| format!("{:.2},{:.2}", sx(x), sy(y)))
                .collect();
            let dash = if ser.dashed {
                r#" stroke-dasharray="6 4""#
            } else {
                ""
            };
            let _ = writeln!(
                s,
                r#"<polyline fill="none" stroke="{}" stroke-width="1.4"{dash} points="{}"/>"#,
                ser.color,
                pts.join(" ")
            );
            let ly = mt + 14.0 + 16.0 * i as f64;
            let _ = writeln!(
                s,
                r#"<line x1="{:.1}" y1="{ly:.1}" x2="{:.1}" y2="{ly:.1}" stroke="{}" stroke-width="2"{dash}/><text x="{:.1}" y="{:.1}">{}</text>"#,
                ml + 10.0,
                ml + 34.0,
                ser.color,
                ml + 40.0,
                ly + 4.0,
                ser.label
            );
        }
        for (x, y, label) in &self.markers {
            let _ = writeln!(
                s,
                r##"<circle cx="{:.1}" cy="{:.1}" r="3" fill="#c00"/><text x="{:.1}" y="{:.1}" fill="#c00" font-size="10">{label}</text>"##,
                sx(*x),
                sy(*y),
                sx(*x) + 4.0,
                sy(*y) - 4.0
            );
        }
        s.push_str("</svg>\n");
        std::fs::write(path, s).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        println!("wrote {}", path.display());
    }
}

/// A labelled point of a figure.
type Marker = (f64, f64, String);

/// Drives `el` along `path` in steps of at most `h`; returns the (twist,
/// torque) points and the control points of every rule branch started on
/// the way, labelled.
fn trace<const N: usize, const M: usize>(
    el: &mut Phm<f64, N, M>,
    path: &[f64],
    h: f64,
) -> (Vec<(f64, f64)>, Vec<Marker>) {
    let mut pts = vec![(el.displacement(), el.response().force)];
    let mut marks = Vec::new();
    for &to in path {
        while el.displacement() != to {
            let x0 = el.displacement();
            let x = if (to - x0).abs() <= h {
                to
            } else {
                x0 + h * (to - x0).signum()
            };
            let before = el.committed().dir();
            el.set_trial(x).unwrap();
            let b = *el.branch();
            if b.dir() != before && b.kind() == Kind::Rule {
                for (v, name) in b.vertices().zip(labels(&b, el.params())) {
                    if let Some(name) = name {
                        marks.push((b.dir() * v[0], b.dir() * v[1], name.to_string()));
                    }
                }
            }
            el.commit();
            pts.push((x, el.response().force));
        }
    }
    (pts, marks)
}

/// Names of the control points of a rule branch: the reversal point P, the
/// unloading points (eqs 1-2), the zero-torque point su (eq. 3), then the
/// reloading points: the crack-closing point cr and the target m' (eqs 5-6),
/// or the other direction's cracking point c (rule 2); the helper vertex of
/// an eq. 4 line is not a control point and is left unnamed.
fn labels<const N: usize>(b: &Branch<f64>, p: &PhmParams<f64, N>) -> Vec<Option<&'static str>> {
    let v: Vec<[f64; 2]> = b.vertices().collect();
    let zero = v.iter().position(|q| q[1] >= 0.0).unwrap_or(v.len());
    let unloading: &[&str] = match zero {
        2 => &["P", "ur1", "su"],
        3 => &["P", "ur1", "ur2", "su"],
        _ => &["P", "", "", "", ""],
    };
    let side = if b.dir() > 0.0 {
        Direction::Positive
    } else {
        Direction::Negative
    };
    let crack = p.primary(side).cracking();
    let mut out: Vec<Option<&'static str>> = (0..=zero.min(v.len() - 1))
        .map(|i| unloading.get(i).copied().filter(|s| !s.is_empty()))
        .collect();
    match &v[zero + 1..] {
        [c] if *c == crack => out.push(Some("c")),
        [_] => out.push(None),
        [_, _] => out.extend([Some("cr"), Some("m'")]),
        _ => {}
    }
    out
}

fn rules_figure() {
    let curve = [[1.0, 10.0], [5.0, 20.0], [10.0, 20.0], [15.0, 16.0]];
    let p = PhmParams::<f64, 4>::symmetric(&curve, Coefficients::thesis()).unwrap();
    let mut el: Phm<f64, 4, 16> = Phm::new(p);
    let history = [
        0.6, -0.6, 3.0, -3.0, 8.0, -8.0, 8.0, 7.0, 7.6, -8.0, 12.0, -12.0,
    ];
    let (pts, marks) = trace(&mut el, &history, 0.02);
    let mut envelope = vec![];
    for s in [-1.0, 1.0] {
        let mut side: Vec<(f64, f64)> = std::iter::once([0.0, 0.0])
            .chain(curve.iter().copied())
            .map(|[x, y]| (s * x, s * y))
            .collect();
        side.push((s * 16.0, s * 16.0));
        if s < 0.0 {
            side.reverse();
        }
        envelope.extend(side);
    }
    Plot {
        title: "PHM rule paths (thesis ch. 5) on the curve (1,10) (5,20) (10,20) (15,16)".into(),
        xlabel: "twist",
        ylabel: "torque",
        series: vec![
            Series {
                label: "primary curve".into(),
                color: "#888",
                dashed: true,
                points: envelope,
            },
            Series {
                label: "PHM: 0.6, -0.6, 3, -3, 8, -8, 8, 7, 7.6, -8, 12, -12".into(),
                color: "#1f4e9c",
                dashed: false,
                points: pts,
            },
        ],
        markers: marks,
    }
    .write(&root().join("docs/phm-rules.svg"));
}

/// Dissipated energy (∮ T dθ) per block of `len` steps.
fn energy_blocks(theta: &[f64], torque: &[f64], len: usize) -> Vec<f64> {
    let mut out = vec![0.0; theta.len() / len + 1];
    for i in 1..theta.len() {
        out[(i - 1) / len] += 0.5 * (torque[i] + torque[i - 1]) * (theta[i] - theta[i - 1]);
    }
    out.truncate((theta.len() - 1) / len);
    out
}

fn compare() {
    let dir = root().join("../shared/data/opensees-reference");
    let history: Vec<f64> = read_csv(&dir.join("history.csv"))
        .iter()
        .map(|r| r[1])
        .collect();
    let hysteretic = [[1.0, 5.0], [4.0, 6.5], [8.0, 5.5]];
    let pinching4 = [[1.0, 5.0], [3.0, 6.3], [6.0, 6.5], [10.0, 5.0]];
    let cases: [(&str, &[[f64; 2]]); 5] = [
        ("Hysteretic_pinch", &hysteretic),
        ("Hysteretic_pinch_damage", &hysteretic),
        ("Pinching4_energy", &pinching4),
        ("Pinching4_moderate_energy", &pinching4),
        ("Pinching4_moderate_cycle", &pinching4),
    ];
    let amplitudes = [0.5, 1.0, 2.0, 4.0, 6.0, 8.0];
    let mut table = String::new();
    let _ = writeln!(
        table,
        "| case | RMS diff (kN) | max diff (kN) | energy PHM / OpenSees, per amplitude block 0.5 1 2 4 6 8 mm (kN mm) | 3rd-cycle peak +A at 4 / 8 mm, PHM vs OpenSees (kN) |"
    );
    let _ = writeln!(table, "|---|---:|---:|---|---|");
    for (name, curve) in cases {
        let rows = read_csv(&dir.join(format!("{name}.csv")));
        let reference: Vec<f64> = rows.iter().map(|r| r[2]).collect();
        let p = PhmParams::<f64, 4>::symmetric(curve, Coefficients::thesis()).unwrap();
        let mut el: Phm<f64, 4, 16> = Phm::new(p);
        let phm: Vec<f64> = history
            .iter()
            .map(|&x| {
                let r = el.set_trial(x).unwrap();
                el.commit();
                r.force
            })
            .collect();
        let n = history.len() as f64;
        let rms = (phm
            .iter()
            .zip(&reference)
            .map(|(a, b)| (a - b).powi(2))
            .sum::<f64>()
            / n)
            .sqrt();
        let max = phm
            .iter()
            .zip(&reference)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        let ep = energy_blocks(&history, &phm, 600);
        let er = energy_blocks(&history, &reference, 600);
        let energies: Vec<String> = ep
            .iter()
            .zip(&er)
            .map(|(a, b)| format!("{a:.1}/{b:.1}"))
            .collect();
        // Third cycle of each amplitude block: peak at step 600 k + 400 + 50.
        let peak = |v: &[f64], block: usize| v[600 * block + 450];
        let peaks = format!(
            "{:.2} vs {:.2} / {:.2} vs {:.2}",
            peak(&phm, 3),
            peak(&reference, 3),
            peak(&phm, 5),
            peak(&reference, 5)
        );
        assert!(amplitudes.len() == ep.len());
        let _ = writeln!(
            table,
            "| {name} | {rms:.3} | {max:.3} | {} | {peaks} |",
            energies.join(", ")
        );
        Plot {
            title: format!("PHM (thesis rules) vs OpenSees {name}, same primary curve"),
            xlabel: "displacement / twist (mm)",
            ylabel: "force / torque (kN)",
            series: vec![
                Series {
                    label: format!("OpenSees {name}"),
                    color: "#d9822b",
                    dashed: false,
                    points: history
                        .iter()
                        .copied()
                        .zip(reference.iter().copied())
                        .collect(),
                },
                Series {
                    label: "PHM".into(),
                    color: "#1f4e9c",
                    dashed: false,
                    points: history.iter().copied().zip(phm.iter().copied()).collect(),
                },
            ],
            markers: vec![],
        }
        .write(&root().join(format!("docs/phm-vs-{name}.svg")));
    }
    print!("{table}");
}

fn main() {
    std::fs::create_dir_all(root().join("docs")).expect("docs folder");
    rules_figure();
    compare();
}
