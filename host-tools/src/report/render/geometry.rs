//! Rectangles and the mapping from data values to pixels.

/// Pixel coordinates are kept inside this box so that a point far outside
/// fixed axis limits cannot produce absurd numbers in the file.
pub(super) const FAR: f64 = 1e5;

/// An axis-aligned rectangle in pixels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Rect {
    pub(super) x0: f64,
    pub(super) y0: f64,
    pub(super) x1: f64,
    pub(super) y1: f64,
}

impl Rect {
    pub(super) fn w(&self) -> f64 {
        self.x1 - self.x0
    }

    pub(super) fn h(&self) -> f64 {
        self.y1 - self.y0
    }

    pub(super) fn contains(&self, (x, y): (f64, f64)) -> bool {
        x >= self.x0 && x <= self.x1 && y >= self.y0 && y <= self.y1
    }

    pub(super) fn overlaps(&self, o: &Rect) -> bool {
        self.x0 < o.x1 && o.x0 < self.x1 && self.y0 < o.y1 && o.y0 < self.y1
    }

    /// Whether the segment `a`–`b` passes through this rectangle
    /// (Liang–Barsky clipping).
    pub(super) fn crossed_by(&self, a: (f64, f64), b: (f64, f64)) -> bool {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
        for (p, q) in [
            (-dx, a.0 - self.x0),
            (dx, self.x1 - a.0),
            (-dy, a.1 - self.y0),
            (dy, self.y1 - a.1),
        ] {
            if p == 0.0 {
                if q < 0.0 {
                    return false;
                }
            } else {
                let r = q / p;
                if p < 0.0 {
                    t0 = t0.max(r);
                } else {
                    t1 = t1.min(r);
                }
                if t0 > t1 {
                    return false;
                }
            }
        }
        true
    }
}

/// Maps data values on one axis to pixels.
#[derive(Debug, Clone, Copy)]
pub(super) struct Map {
    pub(super) lo: f64,
    pub(super) hi: f64,
    pub(super) p0: f64,
    pub(super) p1: f64,
    pub(super) log: bool,
}

impl Map {
    /// Pixel position of `v`, or `None` where the scale cannot show it.
    pub(super) fn px(&self, v: f64) -> Option<f64> {
        if !v.is_finite() || (self.log && v <= 0.0) {
            return None;
        }
        let t = if self.log {
            (v.log10() - self.lo.log10()) / (self.hi.log10() - self.lo.log10())
        } else {
            // Halves keep `hi - lo` finite near f64::MAX.
            (v / 2.0 - self.lo / 2.0) / (self.hi / 2.0 - self.lo / 2.0)
        };
        Some((self.p0 + t * (self.p1 - self.p0)).clamp(-FAR, FAR))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segment_crossing_is_exact_at_the_edges() {
        let r = Rect {
            x0: 0.0,
            y0: 0.0,
            x1: 10.0,
            y1: 10.0,
        };
        assert!(r.crossed_by((-5.0, 5.0), (15.0, 5.0)));
        assert!(r.crossed_by((5.0, 5.0), (6.0, 6.0)));
        assert!(!r.crossed_by((-5.0, -1.0), (15.0, -1.0)));
        assert!(!r.crossed_by((11.0, -5.0), (20.0, 5.0)));
        assert!(r.crossed_by((-1.0, 9.0), (1.0, 11.0)));
    }
}
