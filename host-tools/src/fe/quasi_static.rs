//! Honesty checks of a quasi-static run (thesis 2.3): a dynamic solution
//! stands for a static one only while inertia is negligible. Every step's
//! energies are recorded, and a run is judged over the steps after its
//! internal energy first reaches [`WINDOW_START`] of its maximum (at the
//! very start every load history has more kinetic than internal energy):
//!
//! * kinetic / internal energy below [`KE_IE_LIMIT`] (Zimmermann 2001);
//! * hourglass / internal energy below [`HOURGLASS_LIMIT`];
//! * energy balance `|W - IE - VD - KE|` below [`BALANCE_LIMIT`] of
//!   `max(W, IE + VD + KE)`.
//!
//! A run that peaks is also judged as if it had ended at its peak torque
//! ([`EnergyTrace::verdict_until`]): the curve up to the peak can be
//! quasi-static while the collapse after it is not.

use super::explicit::Energies;

/// Largest admissible kinetic to internal energy ratio.
pub const KE_IE_LIMIT: f64 = 0.1;
/// Largest admissible hourglass share of the internal energy.
pub const HOURGLASS_LIMIT: f64 = 0.05;
/// Largest admissible energy imbalance, relative.
pub const BALANCE_LIMIT: f64 = 0.01;
/// The judged window starts when the internal energy first reaches this
/// fraction of its maximum.
pub const WINDOW_START: f64 = 0.01;

/// Energies of every step.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct EnergyTrace {
    t: Vec<f64>,
    e: Vec<Energies>,
}

impl EnergyTrace {
    /// Records the energies at time `t`.
    pub fn push(&mut self, t: f64, e: Energies) {
        self.t.push(t);
        self.e.push(e);
    }

    /// Judges the run so far.
    pub fn verdict(&self) -> Verdict {
        self.verdict_until(f64::INFINITY)
    }

    /// Judges the run up to and including time `t_end`, as if it had ended
    /// there: the window starts where the internal energy first reaches
    /// [`WINDOW_START`] of its maximum up to `t_end`. This gives a run's
    /// checks up to its peak torque, before the collapse of crushed
    /// concrete, whose hourglass and kinetic energies say nothing about the
    /// curve up to the peak; they depend on the run up to the peak alone,
    /// not on where it ends.
    pub fn verdict_until(&self, t_end: f64) -> Verdict {
        let steps = self.t.partition_point(|&t| t <= t_end);
        let (t, e) = (&self.t[..steps], &self.e[..steps]);
        let ie_max = e.iter().fold(0.0f64, |m, e| m.max(e.internal()));
        let start = e
            .iter()
            .position(|e| ie_max > 0.0 && e.internal() >= WINDOW_START * ie_max)
            .unwrap_or(steps);
        let mut v = Verdict {
            window_start: t.get(start).copied().unwrap_or(f64::NAN),
            max_ke_ie_ratio: 0.0,
            at: f64::NAN,
            max_hourglass_share: 0.0,
            final_hourglass_share: 0.0,
            max_imbalance: 0.0,
            steps,
        };
        for (t, e) in t[start..].iter().zip(&e[start..]) {
            let ie = e.internal();
            let r = e.kinetic / ie;
            if !(r <= v.max_ke_ie_ratio) {
                v.max_ke_ie_ratio = r;
                v.at = *t;
            }
            v.max_hourglass_share = v.max_hourglass_share.max(e.hourglass / ie);
            let scale = e.work.abs().max(ie + e.viscous + e.kinetic);
            v.max_imbalance = v.max_imbalance.max(e.imbalance().abs() / scale);
        }
        if let Some(e) = e.last() {
            v.final_hourglass_share = e.hourglass / e.internal();
        }
        v
    }
}

/// The outcome of the checks.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Verdict {
    /// Time the judged window starts, s.
    pub window_start: f64,
    /// Largest kinetic / internal energy ratio in the window.
    pub max_ke_ie_ratio: f64,
    /// When it occurred, s.
    pub at: f64,
    /// Largest hourglass share of the internal energy in the window.
    pub max_hourglass_share: f64,
    /// Hourglass share at the end.
    pub final_hourglass_share: f64,
    /// Largest relative energy imbalance in the window.
    pub max_imbalance: f64,
    /// Steps recorded.
    pub steps: usize,
}

impl Verdict {
    /// The broken checks, as sentences; empty when the run is quasi-static.
    pub fn failures(&self) -> Vec<String> {
        let mut f = Vec::new();
        if !(self.max_ke_ie_ratio < KE_IE_LIMIT) {
            f.push(format!(
                "kinetic/internal energy reached {:.3} at t = {:.4e} s (limit {KE_IE_LIMIT}): \
                 inertia matters, load more slowly",
                self.max_ke_ie_ratio, self.at
            ));
        }
        if !(self.max_hourglass_share < HOURGLASS_LIMIT) {
            f.push(format!(
                "hourglass energy reached {:.1}% of internal energy (limit {:.0}%): refine the mesh",
                100.0 * self.max_hourglass_share,
                100.0 * HOURGLASS_LIMIT
            ));
        }
        if !(self.max_imbalance < BALANCE_LIMIT) {
            f.push(format!(
                "energy balance off by {:.2}% (limit {:.0}%): the time step may be unstable",
                100.0 * self.max_imbalance,
                100.0 * BALANCE_LIMIT
            ));
        }
        f
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn e(strain: f64, hourglass: f64, kinetic: f64, work: f64) -> Energies {
        Energies {
            strain,
            hourglass,
            viscous: 0.0,
            kinetic,
            work,
        }
    }

    #[test]
    fn window_skips_the_start_and_catches_violations() {
        let mut tr = EnergyTrace::default();
        tr.push(0.0, e(0.0, 0.0, 1e-6, 1e-6));
        tr.push(1.0, e(0.005, 0.0, 0.01, 0.015));
        tr.push(2.0, e(0.5, 0.01, 0.01, 0.52));
        tr.push(3.0, e(1.0, 0.02, 0.2, 1.22));
        let v = tr.verdict();
        assert_eq!(v.window_start, 2.0);
        assert!((v.max_ke_ie_ratio - 0.2 / 1.02).abs() < 1e-12);
        assert_eq!(v.at, 3.0);
        assert_eq!(v.failures().len(), 1);
        let mut bad = tr.clone();
        bad.push(4.0, e(1.0, 0.1, 0.0, 2.0));
        let f = bad.verdict().failures();
        assert_eq!(f.len(), 3, "{f:?}");
    }

    #[test]
    fn a_run_is_judged_up_to_its_peak_as_if_it_had_ended_there() {
        let mut tr = EnergyTrace::default();
        tr.push(0.0, e(0.0, 0.0, 1e-6, 1e-6));
        tr.push(1.0, e(0.5, 0.01, 0.01, 0.52));
        tr.push(2.0, e(1.0, 0.02, 0.02, 1.04));
        // The collapse: hourglass and kinetic energy grow.
        tr.push(3.0, e(1.0, 0.2, 0.3, 1.5));
        let whole = tr.verdict();
        assert_eq!(whole.failures().len(), 2, "{:?}", whole.failures());
        for t_end in [2.0, 2.5] {
            let v = tr.verdict_until(t_end);
            assert_eq!(v.steps, 3);
            assert!(v.failures().is_empty(), "{:?}", v.failures());
            assert!((v.max_hourglass_share - 0.02 / 1.02).abs() < 1e-12);
            assert!((v.final_hourglass_share - 0.02 / 1.02).abs() < 1e-12);
            assert_eq!(v.window_start, whole.window_start);
        }
        assert_eq!(tr.verdict_until(10.0), whole);
        // Before the window: nothing judged.
        let early = tr.verdict_until(0.5);
        assert_eq!(early.max_hourglass_share, 0.0);
        assert!(early.failures().is_empty());
    }

    #[test]
    fn the_checks_up_to_a_time_do_not_depend_on_what_follows_it() {
        // Internal energy 0.05 at t = 1 is 5% of the maximum up to t = 2
        // but 0.05% of the whole run's: judged up to t = 2, the start-up
        // kinetic energy at t = 1 is inside the window; judged whole, not.
        let mut tr = EnergyTrace::default();
        tr.push(0.0, e(0.0, 0.0, 1e-6, 1e-6));
        tr.push(1.0, e(0.05, 0.0, 0.03, 0.08));
        tr.push(2.0, e(1.0, 0.0, 0.01, 1.01));
        let ended = tr.clone();
        tr.push(3.0, e(100.0, 0.0, 0.5, 100.5));
        assert_eq!(tr.verdict().window_start, 2.0);
        let v = tr.verdict_until(2.0);
        assert_eq!(v, ended.verdict());
        assert_eq!(v.window_start, 1.0);
        assert!((v.max_ke_ie_ratio - 0.6).abs() < 1e-12);
        assert_eq!(v.failures().len(), 1, "{:?}", v.failures());
    }
}
