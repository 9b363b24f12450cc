//! The speed of loading, `v = du/dt`, which a dashpot's force follows: the
//! rate-dependence check of `hyst diagnose` fits one
//! ([`crate::discover::rate`]) and `--dashpot` takes one off a record
//! ([`Record::take_dashpot`](super::Record::take_dashpot)), both with this
//! estimate.

/// Half-width (samples) of the central difference.
pub const HALF_WIDTH: usize = 2;

/// The speed of `u` sampled at the times `t`, by central differences over
/// [`HALF_WIDTH`] samples each side (one-sided at the ends); `None` for fewer
/// than three samples, lengths that differ or times that do not increase
/// across a difference (a record's times are checked to increase when it is
/// read).
///
/// ```
/// use hyst::data::speed;
/// let t = [0.0, 0.1, 0.2, 0.3, 0.4];
/// let u = [0.0, 0.3, 0.6, 0.9, 1.2];
/// for v in speed::of(&u, &t).unwrap() {
///     assert!((v - 3.0).abs() < 1e-12);
/// }
/// assert!(speed::of(&u, &[0.4, 0.3, 0.2, 0.1, 0.0]).is_none());
/// assert!(speed::of(&u, &t[..4]).is_none());
/// ```
pub fn of(u: &[f64], t: &[f64]) -> Option<Vec<f64>> {
    let n = u.len();
    if n < 3 || t.len() != n {
        return None;
    }
    (0..n)
        .map(|i| {
            let (a, b) = (i.saturating_sub(HALF_WIDTH), (i + HALF_WIDTH).min(n - 1));
            let dt = t[b] - t[a];
            (dt > 0.0).then(|| (u[b] - u[a]) / dt)
        })
        .collect()
}
