//! Load and displacement histories as tables of `(time, value)`, between
//! points either linear or a smooth step (ABAQUS' smooth-step amplitude:
//! `v = v_i + (v_{i+1} - v_i) s^3 (10 - 15 s + 6 s^2)`, zero rate and
//! acceleration at every table point). Before the first point the value is
//! the first value, after the last the last.

/// Interpolation between table points.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Interpolation {
    /// Straight lines.
    Linear,
    /// Quintic smooth steps.
    SmoothStep,
}

/// A history table.
#[derive(Clone, Debug, PartialEq)]
pub struct History {
    points: Vec<(f64, f64)>,
    interp: Interpolation,
}

impl History {
    /// A table; times must increase strictly (checked by the specimen
    /// reader).
    pub fn new(points: Vec<(f64, f64)>, interp: Interpolation) -> History {
        History { points, interp }
    }

    /// A constant value.
    pub fn constant(v: f64) -> History {
        History::new(vec![(0.0, v)], Interpolation::Linear)
    }

    /// The value at time `t`.
    pub fn value(&self, t: f64) -> f64 {
        let p = &self.points;
        let Some(&(t0, v0)) = p.first() else {
            return 0.0;
        };
        if t <= t0 {
            return v0;
        }
        for w in p.windows(2) {
            let ((ta, va), (tb, vb)) = (w[0], w[1]);
            if t <= tb {
                let s = (t - ta) / (tb - ta);
                let f = match self.interp {
                    Interpolation::Linear => s,
                    Interpolation::SmoothStep => s * s * s * (10.0 - 15.0 * s + 6.0 * s * s),
                };
                return va + (vb - va) * f;
            }
        }
        p[p.len() - 1].1
    }

    /// Time of the last point.
    pub fn end(&self) -> f64 {
        self.points.last().map_or(0.0, |p| p.0)
    }

    /// The largest absolute value of the table.
    pub fn max_abs(&self) -> f64 {
        self.points.iter().fold(0.0, |m, p| m.max(p.1.abs()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn smooth_step_starts_and_stops_at_rest() {
        let h = History::new(vec![(0.0, 0.0), (1.0, 2.0)], Interpolation::SmoothStep);
        assert_eq!(h.value(-1.0), 0.0);
        assert_eq!(h.value(0.5), 1.0);
        assert_eq!(h.value(2.0), 2.0);
        let e = 1e-4;
        assert!(h.value(e) < 1e-10);
        assert!((h.value(1.0 - e) - 2.0).abs() < 1e-10);
    }

    #[test]
    fn linear_table() {
        let h = History::new(
            vec![(1.0, 0.0), (2.0, 1.0), (4.0, -1.0)],
            Interpolation::Linear,
        );
        assert_eq!(h.value(1.5), 0.5);
        assert_eq!(h.value(3.0), 0.0);
        assert_eq!(h.end(), 4.0);
        assert_eq!(h.max_abs(), 1.0);
        assert_eq!(History::constant(3.0).value(10.0), 3.0);
    }
}
