//! The binary-coded variant the thesis describes (section 3.3): each variable is a string of
//! `bits` bits, 00...0 mapped to its lower bound and 11...1 to its upper bound with the
//! 2^bits - 1 steps between them equal; children come from a random cross site on the
//! concatenated strings (single point, as the thesis describes, or two points as in Deb's
//! reference code) and from bit flips.
//!
//! A genome holds one word per variable, bit `bits - 1` first in the string (the thesis writes
//! the most significant bit on the left).

use super::{BinaryCrossover, Bounds};
use crate::random::Rng;

/// The most bits a variable may have: every decoded value is then exact in an `f64`.
pub const MAX_BITS: u32 = 52;

/// The decoded value of the `bits`-bit string `word` between `bounds`.
pub(super) fn decode(word: u64, bits: u32, bounds: Bounds) -> f64 {
    let steps = ((1u64 << bits) - 1) as f64;
    let value = bounds.lower + (bounds.upper - bounds.lower) * (word as f64 / steps);
    // lower + (upper - lower) * 1 can round one ulp past `upper`.
    value.min(bounds.upper)
}

/// A random string of `bits` bits.
pub(super) fn random_word(bits: u32, rng: &mut Rng) -> u64 {
    rng.next_u64() & mask(bits)
}

fn mask(bits: u32) -> u64 {
    if bits == 64 {
        u64::MAX
    } else {
        (1u64 << bits) - 1
    }
}

/// Crosses `a` and `b` in place with probability `p` (whole-string operators) or each variable
/// with probability `p` (per variable). Cut sites of the whole string are drawn uniformly among
/// the `len - 1` places between two of its bits; the bits after a single site (or between two
/// sites) are exchanged. Per variable, two sites are drawn among the `bits + 1` places of the
/// variable's string (its ends included) and the bits between them exchanged.
pub(super) fn crossover(
    a: &mut [u64],
    b: &mut [u64],
    bits: u32,
    kind: BinaryCrossover,
    p: f64,
    rng: &mut Rng,
) {
    let len = a.len() * bits as usize;
    match kind {
        BinaryCrossover::SinglePoint | BinaryCrossover::TwoPoint if len < 2 => {}
        BinaryCrossover::SinglePoint => {
            if rng.chance(p) {
                let site = 1 + rng.below(len - 1);
                swap_tail(a, b, bits, site);
            }
        }
        BinaryCrossover::TwoPoint => {
            if rng.chance(p) {
                let s1 = 1 + rng.below(len - 1);
                let s2 = 1 + rng.below(len - 1);
                // Exchanging the tails at both sites exchanges exactly the bits between them.
                swap_tail(a, b, bits, s1);
                swap_tail(a, b, bits, s2);
            }
        }
        BinaryCrossover::PerVariable => {
            let places = bits as usize + 1;
            for (wa, wb) in a.iter_mut().zip(b.iter_mut()) {
                if !rng.chance(p) {
                    continue;
                }
                let (s1, s2) = (rng.below(places) as u32, rng.below(places) as u32);
                // Positions s..bits of the string are its lowest bits - s bits.
                let m = mask(bits - s1.min(s2)) & !mask(bits - s1.max(s2));
                let diff = (*wa ^ *wb) & m;
                *wa ^= diff;
                *wb ^= diff;
            }
        }
    }
}

/// Exchanges the bits at string positions `site..` (position 0 is the first bit of the first
/// variable).
fn swap_tail(a: &mut [u64], b: &mut [u64], bits: u32, site: usize) {
    let width = bits as usize;
    for (v, (wa, wb)) in a.iter_mut().zip(b.iter_mut()).enumerate() {
        let start = v * width;
        if start + width <= site {
            continue;
        }
        // Positions site.. of this variable are its lowest `tail` bits.
        let tail = (start + width - site.max(start)) as u32;
        let m = mask(tail);
        let diff = (*wa ^ *wb) & m;
        *wa ^= diff;
        *wb ^= diff;
    }
}

/// Flips each bit of the genome independently with probability `p`.
pub(super) fn bit_flip(genome: &mut [u64], bits: u32, p: f64, rng: &mut Rng) {
    for word in genome {
        for bit in 0..bits {
            if rng.chance(p) {
                *word ^= 1u64 << bit;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_thesis_three_bit_strings_map_onto_eight_equal_steps() {
        let b = Bounds::new(-1.0, 6.0);
        assert_eq!(decode(0b000, 3, b), -1.0);
        assert_eq!(decode(0b111, 3, b), 6.0);
        assert_eq!(decode(0b001, 3, b), 0.0);
        assert_eq!(decode(0b110, 3, b), 5.0);
        let wide = Bounds::new(0.1, 0.3);
        assert_eq!(decode(mask(MAX_BITS), MAX_BITS, wide), 0.3);
        assert_eq!(decode(0, MAX_BITS, wide), 0.1);
    }

    #[test]
    fn single_point_crossover_exchanges_exactly_one_side_of_the_site() {
        // Two variables of 4 bits: a = 0000 0000, b = 1111 1111. Whatever the site, each child
        // is a run of one parent's bits followed by the other's: 0..01..1 and 1..10..0.
        let mut rng = Rng::seed_from_u64(12);
        let mut sites_seen = [false; 8];
        for _ in 0..500 {
            let (mut a, mut b) = (vec![0b0000, 0b0000], vec![0b1111, 0b1111]);
            crossover(
                &mut a,
                &mut b,
                4,
                BinaryCrossover::SinglePoint,
                1.0,
                &mut rng,
            );
            let sa = (a[0] << 4) | a[1];
            let sb = (b[0] << 4) | b[1];
            assert_eq!(sa ^ sb, 0xff, "children are complements");
            let ones = sa.count_ones() as usize;
            assert!((1..8).contains(&ones), "site strictly inside the string");
            assert_eq!(sa, (1 << ones) - 1, "a child is 0..01..1: {sa:08b}");
            sites_seen[8 - ones] = true;
        }
        assert_eq!(sites_seen[1..], [true; 7], "all seven sites drawn");
    }

    #[test]
    fn two_point_crossover_exchanges_one_segment() {
        let mut rng = Rng::seed_from_u64(13);
        for _ in 0..500 {
            let (mut a, mut b) = (vec![0u64; 3], vec![0b11111u64; 3]);
            crossover(&mut a, &mut b, 5, BinaryCrossover::TwoPoint, 1.0, &mut rng);
            let sa = (a[0] << 10) | (a[1] << 5) | a[2];
            let sb = (b[0] << 10) | (b[1] << 5) | b[2];
            assert_eq!(sa ^ sb, (1 << 15) - 1);
            // The ones of child a form one contiguous run (possibly empty when the sites coincide).
            if sa != 0 {
                let shifted = sa >> sa.trailing_zeros();
                assert_eq!(shifted & (shifted + 1), 0, "one segment: {sa:015b}");
            }
        }
    }

    #[test]
    fn per_variable_crossover_exchanges_one_segment_of_each_crossed_variable() {
        let mut rng = Rng::seed_from_u64(15);
        let mut crossed = 0;
        let mut lengths_seen = [false; 7];
        for _ in 0..1_000 {
            let (mut a, mut b) = (vec![0u64; 4], vec![0b111111u64; 4]);
            crossover(
                &mut a,
                &mut b,
                6,
                BinaryCrossover::PerVariable,
                0.75,
                &mut rng,
            );
            for (wa, wb) in a.iter().zip(&b) {
                assert_eq!(wa ^ wb, 0b111111);
                if *wa != 0 {
                    crossed += 1;
                    let shifted = wa >> wa.trailing_zeros();
                    assert_eq!(shifted & (shifted + 1), 0, "one segment: {wa:06b}");
                    lengths_seen[wa.count_ones() as usize] = true;
                }
            }
        }
        // A crossed variable exchanges a non-empty segment when its two sites, drawn among 7
        // places, differ (probability 6/7): 4,000 variables x 0.75 x 6/7 = 2,571 expected.
        assert!((crossed as f64 - 2571.4).abs() < 150.0, "crossed {crossed}");
        assert_eq!(
            lengths_seen[1..],
            [true; 6],
            "segments of every length, the whole string included"
        );
    }

    #[test]
    fn bit_flip_flips_each_bit_with_the_given_probability() {
        let mut rng = Rng::seed_from_u64(14);
        let mut flipped = 0u32;
        for _ in 0..2_000 {
            let mut g = vec![0u64; 5];
            bit_flip(&mut g, 20, 0.05, &mut rng);
            flipped += g.iter().map(|w| w.count_ones()).sum::<u32>();
            assert!(g.iter().all(|&w| w < 1 << 20), "no bit beyond the string");
        }
        // 200,000 bits at p = 0.05: 10,000 expected, standard deviation 97.5.
        assert!(
            (f64::from(flipped) - 10_000.0).abs() < 500.0,
            "flipped {flipped}"
        );
    }
}
