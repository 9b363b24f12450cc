//! Fitting the polygonal hysteresis model (thesis ch. 5) to a torque-twist
//! record with the bounded least squares of [`lsq`]: both primary
//! curves (§5.2.1) and the coefficients of eqs 1-6 at once, minimising the
//! NRMSE of the torque.
//!
//! # Variables
//!
//! Per direction (positive first), for a primary curve of K points:
//!
//! * `theta_c`, `T_c`: the cracking point (initial stiffness
//!   `k_T1 = T_c / theta_c`);
//! * for every further point i = 1..K-1 (point 1 is yield): `dtheta{i}`, the
//!   twist increment from point i-1, and `shape{i}`, the segment from point
//!   i-1: `shape >= 0` is its slope as a fraction of `k_T1`
//!   (`T_i = T_(i-1) + shape k_T1 dtheta`), `shape < 0` the fraction the
//!   torque falls by (`T_i = (1 + shape) T_(i-1)`).
//!
//! The bounds make every point of the box a valid primary curve (the rules of
//! `Backbone::new`): increments positive, `shape1` in `[1e-3, 0.999]` (the
//! post-cracking slope positive and no steeper than `k_T1`), later shapes in
//! `[-0.95, 0.999]` (deterioration allowed, the torque stays positive; the
//! upper bound is `0.999`, not 1, so that rounding cannot make a segment
//! steeper than `k_T1`). Twists
//! and torques range over 1/10 to 10 times their start.
//!
//! Then the 30 coefficients of [`SPECS`] (eqs 1a-6 and the band of the cycle
//! counter) by name. Each ranges over its start value scaled by -1 to 3, the
//! range `phm::tests::random_parameters` fuzzes the element over (a start of
//! 0 ranges over ±0.1). `cycle_band` is held at its start: the counter is a
//! threshold, the torque is piecewise constant in it, so its gradient is
//! zero (`--fix cycle_band=...` sets it).
//!
//! # Start
//!
//! From a PHM file, or idealised from the record ([`idealise`]).

use super::identifiability::{self, Identifiability};
use super::lsq::{self, Options};
use super::problem::check_signal;
use crate::model::{simulate_phm, PHM_POINTS};
use anyhow::{anyhow, bail, Result};
use hysteresis::phm::rules::idx;
use hysteresis::phm::{Coefficients, Direction, PhmParams, SPECS};
use nalgebra::DMatrix;

/// One fit variable.
#[derive(Clone, Debug, PartialEq)]
pub struct Variable {
    /// Its name (`positive.theta_c`, `negative.shape2`, `eq4_a`, ...).
    pub name: String,
    /// Start value (or the value it is held at).
    pub start: f64,
    /// Lower bound.
    pub lo: f64,
    /// Upper bound.
    pub hi: f64,
    /// Held at `start`, not fitted.
    pub fixed: bool,
}

/// The variables of one primary curve, `[theta_c, T_c, dtheta1, shape1,
/// ...]` (see the [module docs](self)).
pub fn encode(points: &[[f64; 2]]) -> Vec<f64> {
    let [tc, qc] = points[0];
    let k1 = qc / tc;
    let mut v = vec![tc, qc];
    for w in points.windows(2) {
        let (d, rise) = (w[1][0] - w[0][0], w[1][1] - w[0][1]);
        v.push(d);
        v.push(if rise >= 0.0 {
            rise / (k1 * d)
        } else {
            rise / w[0][1]
        });
    }
    v
}

/// The points of one primary curve from its variables (inverse of
/// [`encode`]).
pub fn decode(v: &[f64]) -> Vec<[f64; 2]> {
    let k1 = v[1] / v[0];
    let mut pts = vec![[v[0], v[1]]];
    for c in v[2..].chunks(2) {
        let [x, y] = pts[pts.len() - 1];
        let (d, s) = (c[0], c[1]);
        let t = if s >= 0.0 {
            y + s * k1 * d
        } else {
            y * (1.0 + s)
        };
        pts.push([x + d, t]);
    }
    pts
}

fn side_name(d: usize) -> &'static str {
    ["positive", "negative"][d]
}

/// The excursions of one direction (`sign` +1 or -1) past the largest twist
/// so far: for each, the indices of its samples that set a new largest
/// twist (consecutive samples), in order.
fn excursions(twist: &[f64], sign: f64) -> Vec<Vec<usize>> {
    let mut far = 0.0;
    let mut runs: Vec<Vec<usize>> = vec![];
    for (i, &x) in twist.iter().enumerate() {
        if sign * x > far {
            far = sign * x;
            match runs.last_mut() {
                Some(run) if run.last() == Some(&i.wrapping_sub(1)) => run.push(i),
                _ => runs.push(vec![i]),
            }
        }
    }
    runs
}

/// The points of one direction (`sign` +1 or -1) known to lie on its
/// primary curve, as `(twist, torque)` magnitudes: every sample of the first
/// excursion (from the virgin state the element follows the curve), then the
/// sample of largest twist of every later excursion past the largest twist
/// so far. The rest of such an excursion is a reloading branch that meets the
/// curve only after the previous extreme (rules 4-6 of §5.2.3), below it.
pub fn first_excursions(twist: &[f64], torque: &[f64], sign: f64) -> Vec<[f64; 2]> {
    let mut env: Vec<[f64; 2]> = vec![];
    for (k, run) in excursions(twist, sign).iter().enumerate() {
        let on_curve = if k == 0 {
            &run[..]
        } else {
            &run[run.len() - 1..]
        };
        env.extend(
            on_curve
                .iter()
                .map(|&i| [sign * twist[i], sign * torque[i]]),
        );
    }
    env.retain(|p| p[1] > 0.0);
    env
}

/// The amplitudes of one direction (`sign` +1 or -1): the largest twist of
/// every excursion that went past the largest twist so far, as magnitudes,
/// increasing. Between two amplitudes the record shows a breakpoint of the
/// primary curve only through the rules' switches (eqs 1-3 change form at
/// the yield twist, the unloading starts on the segment the reversal is on),
/// so a fit cannot move a breakpoint across an amplitude.
pub fn amplitudes(twist: &[f64], sign: f64) -> Vec<f64> {
    excursions(twist, sign)
        .iter()
        .filter_map(|run| run.last().map(|&i| sign * twist[i]))
        .collect()
}

/// Other starts for a fit from `start`: each breakpoint of a primary curve
/// between cracking and the last point moved, one at a time, to the middle
/// of the gap between `amplitudes` (of its direction, [`amplitudes`]) just
/// below and just above the gap it lies in, keeping its torque; only valid
/// curves. Each comes with what was moved. A local fit keeps a breakpoint
/// on its side of every amplitude; these starts put it on the other sides.
pub fn breakpoint_starts(
    start: &PhmParams<f64, PHM_POINTS>,
    amplitudes: [&[f64]; 2],
) -> Vec<(String, PhmParams<f64, PHM_POINTS>)> {
    let dirs = [Direction::Positive, Direction::Negative];
    let curves = dirs.map(|d| start.primary(d).points().to_vec());
    let mut out = vec![];
    for (d, amps) in amplitudes.iter().enumerate() {
        let pts = &curves[d];
        let mut edges = vec![0.0];
        edges.extend_from_slice(amps);
        for j in 1..pts.len().saturating_sub(1) {
            let t = pts[j][0];
            let Some(k) = edges.windows(2).position(|w| w[0] <= t && t < w[1]) else {
                continue;
            };
            for g in [k.checked_sub(1), Some(k + 1)].into_iter().flatten() {
                let Some(w) = edges.get(g..g + 2) else {
                    continue;
                };
                let mid = 0.5 * (w[0] + w[1]);
                if !(pts[j - 1][0] < mid && mid < pts[j + 1][0]) {
                    continue;
                }
                let mut moved = curves.clone();
                moved[d][j][0] = mid;
                if let Ok(p) = PhmParams::new(&moved[0], &moved[1], *start.coefficients()) {
                    let what = format!("{} point {j} at twist {mid:.4}", side_name(d));
                    out.push((what, p));
                }
            }
        }
    }
    out
}

/// A primary curve idealised from the first-excursion envelope of one
/// direction: cracking, yield, peak, last point.
///
/// * initial stiffness `k0`: the median secant `T/theta` of the envelope
///   points below half the peak torque (the first point's secant if there is
///   none);
/// * cracking: the last point up to the peak whose secant is still at least
///   `0.95 k0` (the curve has not yet left the initial line by more than 5 %);
/// * yield: the knee, the point between cracking and peak furthest above the
///   chord from cracking to peak (the peak itself if nothing lies between);
/// * peak: the largest torque, if it comes after yield;
/// * last: the largest twist, if it is 2 % beyond the point before.
///
/// The result is then made valid by [`valid_start`]. `None` if the direction
/// has fewer than 3 envelope points or never softens (no point after
/// cracking).
pub fn idealise(env: &[[f64; 2]]) -> Option<Vec<[f64; 2]>> {
    if env.len() < 3 {
        return None;
    }
    let p = (0..env.len()).max_by(|&a, &b| env[a][1].total_cmp(&env[b][1]))?;
    let tp = env[p][1];
    let secant = |i: usize| env[i][1] / env[i][0];
    let mut low: Vec<f64> = (0..=p)
        .filter(|&i| env[i][1] <= 0.5 * tp)
        .map(secant)
        .collect();
    low.sort_by(f64::total_cmp);
    let k0 = low.get(low.len() / 2).copied().unwrap_or(secant(0));
    let c = (0..=p).rev().find(|&i| secant(i) >= 0.95 * k0)?;
    let last = env.len() - 1;
    if c == last {
        return None;
    }
    let y = if p > c + 1 {
        let [x0, y0] = env[c];
        let k = (tp - y0) / (env[p][0] - x0);
        let above = |i: usize| env[i][1] - (y0 + k * (env[i][0] - x0));
        (c + 1..p)
            .max_by(|&a, &b| above(a).total_cmp(&above(b)))
            .unwrap_or(p)
    } else {
        c + 1
    };
    let mut pts = vec![env[c], env[y]];
    if p > y {
        pts.push(env[p]);
    }
    let tail = pts[pts.len() - 1][0];
    if env[last][0] > 1.02 * tail {
        pts.push(env[last]);
    }
    Some(pts)
}

/// The nearest valid curve to `points` in the variables of [`encode`]:
/// increments at least 1e-6 of the twist span, shapes clamped to their
/// bounds.
pub fn valid_start(points: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let span = points[points.len() - 1][0].abs().max(f64::MIN_POSITIVE);
    let mut v = encode(points);
    v[0] = v[0].max(1e-6 * span);
    v[1] = v[1].max(f64::MIN_POSITIVE);
    for (i, c) in v[2..].chunks_mut(2).enumerate() {
        c[0] = c[0].max(1e-6 * span);
        c[1] = c[1].clamp(if i == 0 { SHAPE1_MIN } else { SHAPE_MIN }, SHAPE_MAX);
    }
    decode(&v)
}

/// The bounds of the variables of [`encode`] around their values `v`.
fn curve_bounds(v: &[f64]) -> (Vec<f64>, Vec<f64>) {
    v.iter()
        .enumerate()
        .map(|(k, &x)| match k {
            3 => (SHAPE1_MIN, SHAPE_MAX),
            k if k >= 2 && k % 2 == 1 => (SHAPE_MIN, SHAPE_MAX),
            _ => (x / 10.0, x * 10.0),
        })
        .unzip()
}

/// The torque of the primary curve `points` at twist `x` (magnitudes):
/// `k_T1 x` up to cracking, linear between points, flat past the last one
/// (gap G7 of `docs/phm.md`).
pub fn primary_at(points: &[[f64; 2]], x: f64) -> f64 {
    let [xc, tc] = points[0];
    if x <= xc {
        return tc / xc * x;
    }
    for w in points.windows(2) {
        if x <= w[1][0] {
            return w[0][1] + (w[1][1] - w[0][1]) / (w[1][0] - w[0][0]) * (x - w[0][0]);
        }
    }
    points[points.len() - 1][1]
}

/// Refines a (valid) start curve by least squares on the first-excursion
/// envelope `env` alone, in the variables of [`encode`] and within their
/// bounds. The envelope is the primary curve itself, and its torque is
/// continuous in the points; the full fit is not (eqs 1-3 switch from the
/// pre- to the post-yield form at the yield twist), so a yield twist that
/// starts on the wrong side of an amplitude of the record stays there.
pub fn fit_envelope(env: &[[f64; 2]], start: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let v0 = encode(start);
    let (lo, hi) = curve_bounds(&v0);
    let f = |v: &[f64]| {
        let pts = decode(v);
        Some(env.iter().map(|p| primary_at(&pts, p[0]) - p[1]).collect())
    };
    lsq::minimize(&f, &v0, &lo, &hi, Options::default())
        .map_or_else(|| start.to_vec(), |s| decode(&s.x))
}

const SHAPE1_MIN: f64 = 1e-3;
const SHAPE_MIN: f64 = -0.95;
/// Not 1: rounding would make a segment of slope `k_T1` a hair steeper.
const SHAPE_MAX: f64 = 0.999;

/// A PHM fit: the record, the variables, and which are held.
#[derive(Clone, Debug)]
pub struct PhmProblem {
    twist: Vec<f64>,
    torque: Vec<f64>,
    /// Points per direction.
    layout: [usize; 2],
    /// All variables: positive curve, negative curve, coefficients.
    pub vars: Vec<Variable>,
    rms: f64,
}

/// The result of [`PhmProblem::solve`].
#[derive(Clone, Debug)]
pub struct PhmOutcome {
    /// The fitted parameter set.
    pub params: PhmParams<f64, PHM_POINTS>,
    /// `RMS(T - T_hat) / RMS(T)`.
    pub nrmse: f64,
    /// Standard error of every free variable, by name (from `s^2 (J^T J)^+`;
    /// infinite where the record does not determine it).
    pub std: Vec<(String, f64)>,
    /// Standard errors of the primary points `[twist, torque]` per direction
    /// (delta method through [`decode`]; 0 for a held point).
    pub point_std: [Vec<[f64; 2]>; 2],
    /// Rank, condition and undetermined variables.
    pub identifiability: Identifiability,
    /// Levenberg-Marquardt iterations.
    pub iterations: usize,
    /// Simulations of the record.
    pub evaluations: usize,
}

impl PhmProblem {
    /// A fit of the record `twist`, `torque` from the start curves
    /// (positive, negative; valid, at most [`PHM_POINTS`] points each) and
    /// start coefficients, holding the `fix`ed variables (names as in
    /// [`Variable::name`]). `units` (twist, torque) name the record's units
    /// in errors: the twist and torque must vary, with finite squares, and
    /// the record must have more samples than free variables.
    pub fn new(
        twist: &[f64],
        torque: &[f64],
        units: [&str; 2],
        start: &PhmParams<f64, PHM_POINTS>,
        fix: &[(String, f64)],
    ) -> Result<Self> {
        let mut vars = vec![];
        let mut layout = [0; 2];
        for (d, dir) in [Direction::Positive, Direction::Negative]
            .into_iter()
            .enumerate()
        {
            let pts = start.primary(dir).points();
            layout[d] = pts.len();
            let v0 = encode(pts);
            let (los, his) = curve_bounds(&v0);
            for (k, v) in v0.into_iter().enumerate() {
                let name = match k {
                    0 => "theta_c".to_string(),
                    1 => "T_c".to_string(),
                    k if k % 2 == 0 => format!("dtheta{}", k / 2),
                    k => format!("shape{}", k / 2),
                };
                let (lo, hi) = (los[k], his[k]);
                vars.push(Variable {
                    name: format!("{}.{name}", side_name(d)),
                    start: v,
                    lo,
                    hi,
                    fixed: false,
                });
            }
        }
        start.coefficients().for_each(|s, v| {
            let (lo, hi) = if v == 0.0 {
                (-0.1, 0.1)
            } else {
                ((-v).min(3.0 * v), (-v).max(3.0 * v))
            };
            vars.push(Variable {
                name: s.name.to_string(),
                start: v,
                lo,
                hi,
                fixed: s.name == SPECS[idx::CYCLE_BAND].name,
            });
        });
        for (name, value) in fix {
            let Some(v) = vars.iter_mut().find(|v| &v.name == name) else {
                bail!(
                    "--fix {name}: not a variable of this fit; the variables are {}",
                    vars.iter()
                        .map(|v| v.name.as_str())
                        .collect::<Vec<_>>()
                        .join(", ")
                );
            };
            if !value.is_finite() {
                bail!("--fix {name}={value}: expected a finite number");
            }
            if fix.iter().filter(|(n, _)| n == name).count() > 1 {
                bail!("`{name}` is fixed twice: fix it once");
            }
            v.start = *value;
            v.fixed = true;
        }
        let n = twist.len();
        if n == 0 || torque.len() != n {
            bail!("expected as many torques as twists, and at least one");
        }
        check_signal("twist", units[0], twist)?;
        check_signal("torque", units[1], torque)?;
        let free = vars.iter().filter(|v| !v.fixed).count();
        if n <= free {
            bail!(
                "the record has {n} sample{}, too few to fit the {free} free variables of the PHM (it needs more samples than variables)",
                if n == 1 { "" } else { "s" }
            );
        }
        let rms = (torque.iter().map(|t| t * t).sum::<f64>() / n as f64).sqrt();
        let p = PhmProblem {
            twist: twist.to_vec(),
            torque: torque.to_vec(),
            layout,
            vars,
            rms,
        };
        p.params(&p.full(&p.free_start()))
            .map_err(|e| anyhow!("the start (with --fix values) is not a valid PHM: {e}"))?;
        Ok(p)
    }

    fn free(&self) -> impl Iterator<Item = &Variable> {
        self.vars.iter().filter(|v| !v.fixed)
    }

    /// The free variables' start values.
    pub fn free_start(&self) -> Vec<f64> {
        self.free().map(|v| v.start).collect()
    }

    /// All variables, with the free ones from `x`.
    fn full(&self, x: &[f64]) -> Vec<f64> {
        let mut it = x.iter();
        self.vars
            .iter()
            .map(|v| {
                if v.fixed {
                    v.start
                } else {
                    *it.next().expect("one value per free variable")
                }
            })
            .collect()
    }

    /// The curves' points of a full variable vector.
    fn curves(&self, full: &[f64]) -> [Vec<[f64; 2]>; 2] {
        let n0 = 2 * self.layout[0];
        let n1 = 2 * self.layout[1];
        [decode(&full[..n0]), decode(&full[n0..n0 + n1])]
    }

    /// The parameter set of a full variable vector.
    fn params(&self, full: &[f64]) -> Result<PhmParams<f64, PHM_POINTS>> {
        let [pos, neg] = self.curves(full);
        let base = pos.len() * 2 + neg.len() * 2;
        let c = Coefficients::from_named(|name| {
            SPECS
                .iter()
                .position(|s| s.name == name)
                .map(|i| full[base + i])
        })
        .map_err(|e| anyhow!("{e}"))?;
        PhmParams::new(&pos, &neg, c).map_err(|e| anyhow!("{e}"))
    }

    /// Residuals `(T_hat - T) / (RMS(T) sqrt(n))`, so that their sum of
    /// squares is the NRMSE squared; `None` if the set is not valid or the
    /// element fails.
    pub fn residuals(&self, x: &[f64]) -> Option<Vec<f64>> {
        let p = self.params(&self.full(x)).ok()?;
        let run = simulate_phm(&p, &self.twist).ok()?;
        let s = 1.0 / (self.rms.max(f64::MIN_POSITIVE) * (self.twist.len() as f64).sqrt());
        Some(
            run.torque
                .iter()
                .zip(&self.torque)
                .map(|(th, t)| (th - t) * s)
                .collect(),
        )
    }

    /// Runs the fit from the start values. `on_iter(iteration, nrmse)` is
    /// called after every accepted step.
    pub fn solve(&self, on_iter: impl FnMut(usize, f64)) -> Result<PhmOutcome> {
        let free: Vec<&Variable> = self.free().collect();
        if free.is_empty() {
            bail!("every variable is fixed: nothing to fit");
        }
        let lo: Vec<f64> = free.iter().map(|v| v.lo).collect();
        let hi: Vec<f64> = free.iter().map(|v| v.hi).collect();
        let f = |x: &[f64]| self.residuals(x);
        let mut on_iter = on_iter;
        let sol = lsq::minimize_observed(
            &f,
            &self.free_start(),
            &lo,
            &hi,
            Options::default(),
            |i, c| on_iter(i, c.sqrt()),
        )
        .ok_or_else(|| anyhow!("the start cannot be simulated"))?;
        let n = self.twist.len();
        let names: Vec<&str> = free.iter().map(|v| v.name.as_str()).collect();
        let cov = identifiability::covariance(&sol.jacobian, sol.cost, n);
        let std = names
            .iter()
            .enumerate()
            .map(|(i, n)| (n.to_string(), cov[(i, i)].sqrt()))
            .collect();
        let point_std = self.point_std(&sol.x, &cov);
        let identifiability = identifiability::analyse(&sol.jacobian, &names, &sol.x, sol.cost, n);
        Ok(PhmOutcome {
            params: self.params(&self.full(&sol.x))?,
            nrmse: sol.cost.sqrt(),
            std,
            point_std,
            identifiability,
            iterations: sol.iterations,
            evaluations: sol.evaluations,
        })
    }

    /// Standard errors of the primary points by the delta method: `g^T C g`
    /// with `g` the derivative of a point coordinate with respect to the free
    /// variables (central differences through [`decode`]).
    fn point_std(&self, x: &[f64], cov: &DMatrix<f64>) -> [Vec<[f64; 2]>; 2] {
        let flat = |x: &[f64]| -> Vec<f64> {
            let [a, b] = self.curves(&self.full(x));
            a.into_iter().chain(b).flatten().collect()
        };
        let m = flat(x).len();
        let mut g = DMatrix::zeros(m, x.len());
        for j in 0..x.len() {
            let h = 1e-7 * x[j].abs().max(1e-9);
            let (mut xp, mut xm) = (x.to_vec(), x.to_vec());
            xp[j] += h;
            xm[j] -= h;
            for (i, (a, b)) in flat(&xp).into_iter().zip(flat(&xm)).enumerate() {
                g[(i, j)] = (a - b) / (2.0 * h);
            }
        }
        let var = |i: usize| {
            let mut v = 0.0;
            for j in 0..x.len() {
                for k in 0..x.len() {
                    if g[(i, j)] != 0.0 && g[(i, k)] != 0.0 {
                        v += g[(i, j)] * cov[(j, k)] * g[(i, k)];
                    }
                }
            }
            v.max(0.0).sqrt()
        };
        let pts: Vec<[f64; 2]> = (0..m / 2).map(|p| [var(2 * p), var(2 * p + 1)]).collect();
        let (a, b) = pts.split_at(self.layout[0]);
        [a.to_vec(), b.to_vec()]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn encode_and_decode_are_inverse() {
        let pts = [[0.2, 100.0], [1.5, 170.0], [4.0, 175.0], [8.0, 140.0]];
        let v = encode(&pts);
        assert!((v[5] - 5.0 / (500.0 * 2.5)).abs() < 1e-12, "{v:?}");
        assert!((v[7] + 35.0 / 175.0).abs() < 1e-12, "{v:?}");
        for (a, b) in decode(&v).iter().zip(&pts) {
            assert!((a[0] - b[0]).abs() < 1e-12 && (a[1] - b[1]).abs() < 1e-12);
        }
    }

    /// Every point of the box is a valid primary curve: corners included.
    #[test]
    fn the_box_holds_only_valid_curves() {
        for corner in 0..16u32 {
            let bit = |k: u32| corner >> k & 1 == 1;
            let v = [
                0.3,
                50.0,
                1.0,
                if bit(0) { SHAPE1_MIN } else { SHAPE_MAX },
                if bit(1) { 1e-6 } else { 5.0 },
                if bit(2) { SHAPE_MIN } else { SHAPE_MAX },
                2.0,
                if bit(3) { SHAPE_MIN } else { SHAPE_MAX },
            ];
            let pts = decode(&v);
            PhmParams::<f64, PHM_POINTS>::symmetric(&pts, Coefficients::thesis())
                .unwrap_or_else(|e| panic!("{pts:?}: {e}"));
        }
    }

    #[test]
    fn idealised_curve_of_a_sampled_primary_curve() {
        // A curve (1, 10) (4, 16) (8, 17) (12, 12) sampled by a ramp.
        let truth = [[1.0, 10.0], [4.0, 16.0], [8.0, 17.0], [12.0, 12.0]];
        let p = PhmParams::<f64, PHM_POINTS>::symmetric(&truth, Coefficients::thesis()).unwrap();
        let twist: Vec<f64> = (0..=240).map(|i| i as f64 * 0.05).collect();
        let run = simulate_phm(&p, &twist).unwrap();
        let env = first_excursions(&twist, &run.torque, 1.0);
        assert_eq!(env.len(), 240);
        let got = idealise(&env).unwrap();
        assert_eq!(got.len(), 4, "{got:?}");
        for (g, t) in got.iter().zip(&truth) {
            assert!(
                (g[0] - t[0]).abs() < 0.1 && (g[1] - t[1]).abs() < 0.3,
                "{got:?}"
            );
        }
        assert!(idealise(&env[..2]).is_none());
    }

    #[test]
    fn later_excursions_give_their_peaks() {
        let twist = [0.0, 1.0, 2.0, 1.0, 0.0, -1.0, 0.0, 1.5, 2.5, 3.0, 2.0];
        let torque = [0.0, 5.0, 6.0, 2.0, 0.0, -5.0, 0.0, 3.0, 6.2, 6.5, 3.0];
        assert_eq!(
            first_excursions(&twist, &torque, 1.0),
            [[1.0, 5.0], [2.0, 6.0], [3.0, 6.5]]
        );
        assert_eq!(first_excursions(&twist, &torque, -1.0), [[1.0, 5.0]]);
        assert_eq!(amplitudes(&twist, 1.0), [2.0, 3.0]);
        assert_eq!(amplitudes(&twist, -1.0), [1.0]);
    }

    /// The curve (1, 10) (3, 14) (6, 15) (9, 12) with amplitudes 2, 4, 5,
    /// 7, 8: yield (3) lies in the gap 2-4, so it moves to 1 (0-2, not past
    /// cracking: dropped) and 4.5 (4-5); the peak (6) lies in 5-7, so it
    /// moves to 4.5 (4-5) and 7.5 (7-8). The last point and cracking stay.
    #[test]
    fn breakpoints_move_to_the_neighbouring_gaps() {
        let pts = [[1.0, 10.0], [3.0, 14.0], [6.0, 15.0], [9.0, 12.0]];
        let start = PhmParams::new(&pts, &pts, Coefficients::thesis()).unwrap();
        let amps = [2.0, 4.0, 5.0, 7.0, 8.0];
        let starts = breakpoint_starts(&start, [&amps, &[]]);
        let moved: Vec<_> = starts
            .iter()
            .map(|(what, p)| {
                (
                    what.as_str(),
                    p.primary(Direction::Positive).points().to_vec(),
                )
            })
            .collect();
        let with = |j: usize, x: f64| {
            let mut p = pts.to_vec();
            p[j][0] = x;
            p
        };
        assert_eq!(
            moved,
            [
                ("positive point 1 at twist 4.5000", with(1, 4.5)),
                ("positive point 2 at twist 4.5000", with(2, 4.5)),
                ("positive point 2 at twist 7.5000", with(2, 7.5)),
            ]
        );
        // The other direction has no amplitudes: nothing moves there.
        assert!(starts
            .iter()
            .all(|(_, p)| p.primary(Direction::Negative).points() == pts));
    }
}
