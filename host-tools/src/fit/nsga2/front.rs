//! What is done with a Pareto front once found: the thesis' choice of one solution (section 3.4,
//! after Ortiz et al. 2013: the minimum Euclidean distance from the origin to the normalised
//! front) and the front as a CSV table.

use std::io::{self, Write};

use super::{Individual, Problem};

/// The index of the point of `front` nearest the origin once every objective is normalised to
/// [0, 1] over the front ((f - min) / (max - min); an objective equal on the whole front
/// normalises to 0). Ties go to the earlier point; `None` for an empty front or one with a
/// non-finite objective value (such a front cannot be normalised).
pub fn closest_to_origin<'a, I>(front: I) -> Option<usize>
where
    I: IntoIterator<Item = &'a [f64]>,
{
    let points: Vec<&[f64]> = front.into_iter().collect();
    let first = points.first()?;
    if points.iter().any(|p| p.iter().any(|v| !v.is_finite())) {
        return None;
    }
    let m = first.len();
    let (mut lo, mut hi) = (vec![f64::INFINITY; m], vec![f64::NEG_INFINITY; m]);
    for p in &points {
        for (k, &v) in p.iter().enumerate() {
            lo[k] = lo[k].min(v);
            hi[k] = hi[k].max(v);
        }
    }
    let distance2 = |p: &[f64]| -> f64 {
        p.iter()
            .enumerate()
            .map(|(k, &v)| {
                let range = hi[k] - lo[k];
                let z = if range > 0.0 {
                    (v - lo[k]) / range
                } else {
                    0.0
                };
                z * z
            })
            .sum()
    };
    let mut best = 0;
    let mut best_d = distance2(first);
    for (i, p) in points.iter().enumerate().skip(1) {
        let d = distance2(p);
        if d < best_d {
            best = i;
            best_d = d;
        }
    }
    Some(best)
}

/// Writes `individuals` as CSV: a header of the problem's variable names, then its objective
/// names, then `constraint_violation` when the problem has constraints; one row per individual,
/// numbers in Rust's shortest round-trip form (read back, they are the same `f64`).
pub fn write_front_csv<W, P>(mut out: W, problem: &P, individuals: &[&Individual]) -> io::Result<()>
where
    W: Write,
    P: Problem + ?Sized,
{
    let mut header: Vec<String> = problem.variable_names();
    header.extend(problem.objective_names());
    let constrained = problem.num_constraints() > 0;
    if constrained {
        header.push("constraint_violation".to_owned());
    }
    let header: Vec<String> = header.iter().map(|h| quoted(h)).collect();
    writeln!(out, "{}", header.join(","))?;
    for ind in individuals {
        let mut row: Vec<String> = ind.variables.iter().map(f64::to_string).collect();
        row.extend(ind.objectives.iter().map(f64::to_string));
        if constrained {
            row.push(ind.total_violation.to_string());
        }
        writeln!(out, "{}", row.join(","))?;
    }
    out.flush()
}

/// A CSV field: as is, or in double quotes with inner quotes doubled when it holds a comma, a
/// quote or a line break (RFC 4180).
fn quoted(field: &str) -> String {
    if field.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", field.replace('"', "\"\""))
    } else {
        field.to_owned()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn knee_of_a_hand_made_convex_front() {
        // f1 in [0, 4], f2 in [0, 16] on the front; normalised:
        // (0,16) -> (0, 1): 1;  (1, 9) -> (0.25, 0.5625): 0.3789;  (2, 4) -> (0.5, 0.25): 0.3125;
        // (3, 1) -> (0.75, 0.0625): 0.5664;  (4, 0) -> (1, 0): 1.  Squared distances; (2, 4) wins.
        let front = [[0.0, 16.0], [1.0, 9.0], [2.0, 4.0], [3.0, 1.0], [4.0, 0.0]];
        assert_eq!(closest_to_origin(front.iter().map(|p| &p[..])), Some(2));
    }

    #[test]
    fn knee_depends_on_normalisation_not_on_units() {
        // In raw units A(0, 10) is nearest the origin (10 against 100.2 and 1000). Normalised
        // over ranges 1000 and 10: A(0, 1) and B(1, 0) at distance 1, C(0.1, 0.6) at 0.608.
        let front = [[0.0, 10.0], [1000.0, 0.0], [100.0, 6.0]];
        assert_eq!(closest_to_origin(front.iter().map(|p| &p[..])), Some(2));
    }

    #[test]
    fn knee_of_degenerate_fronts() {
        let empty: [&[f64]; 0] = [];
        assert_eq!(closest_to_origin(empty), None);
        let single = [[3.0, 4.0]];
        assert_eq!(closest_to_origin(single.iter().map(|p| &p[..])), Some(0));
        let flat = [[1.0, 2.0], [1.0, 2.0]];
        assert_eq!(
            closest_to_origin(flat.iter().map(|p| &p[..])),
            Some(0),
            "tie to the first"
        );
        let bad = [[1.0, f64::NAN], [0.0, 2.0]];
        assert_eq!(closest_to_origin(bad.iter().map(|p| &p[..])), None);
    }

    #[test]
    fn quoting_follows_rfc_4180() {
        assert_eq!(quoted("alpha"), "alpha");
        assert_eq!(quoted("u (mm), rms"), "\"u (mm), rms\"");
        assert_eq!(quoted("say \"hi\""), "\"say \"\"hi\"\"\"");
    }
}
