//! Reinforcing steel for the embedded bars (thesis 2.2.2; issue 8).
//!
//! Thesis 2.2.2: `E = 200 GPa`, Poisson's ratio 0.3 (irrelevant for a
//! uniaxial truss), density 7800 kg/m^3, the same behaviour in tension and
//! compression, yield strengths of Table 1.1 (in the specimen files). The
//! coupon curves (thesis Fig. 2.1, Tirasit 2006, Prakash 2009) are not
//! given as numbers, so the hardening is bilinear with a hardening modulus
//! of 1% of `E` ([`HARDENING_RATIO`]), a usual value for mild reinforcing
//! steel; the yield plateau of a coupon is not modelled.
//!
//! Hardening is isotropic: after yielding to the flow stress
//! `f_y + H eps_p` (with `eps_p` the accumulated plastic strain) the bar
//! unloads elastically and yields in reverse at minus the same flow stress,
//! so there is no Bauschinger effect. For the monotonic twist of chapter 2
//! the bars hardly reverse, and the choice matters little.

use super::material::BarMaterial;

/// Hardening modulus as a fraction of `E`.
pub const HARDENING_RATIO: f64 = 0.01;

/// Elastic-plastic steel with linear isotropic hardening.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HardeningSteel {
    /// Young's modulus, Pa.
    pub e: f64,
    /// Yield strength, Pa.
    pub fy: f64,
    /// Hardening modulus `H` (slope of stress against plastic strain), Pa.
    pub hardening: f64,
    /// Mass density, kg/m^3.
    pub density: f64,
}

impl HardeningSteel {
    /// Thesis 2.2.2 steel of yield strength `fy` (Pa): `E = 200 GPa`,
    /// `H = 0.01 E`, density 7800 kg/m^3.
    pub fn thesis(fy: f64) -> Self {
        let e = 200e9;
        HardeningSteel {
            e,
            fy,
            hardening: HARDENING_RATIO * e,
            density: 7800.0,
        }
    }

    /// Slope of stress against total strain after yield, `E H / (E + H)`.
    pub fn tangent_modulus(&self) -> f64 {
        self.e * self.hardening / (self.e + self.hardening)
    }
}

impl BarMaterial for HardeningSteel {
    /// Accumulated plastic strain.
    type State = f64;

    fn modulus(&self) -> f64 {
        self.e
    }

    fn density(&self) -> f64 {
        self.density
    }

    /// Radial return: elastic trial, then the exact linear-hardening
    /// correction `dp = f / (E + H)`.
    fn update(&self, plastic: &mut f64, deps: f64, stress: &mut f64) {
        let trial = *stress + self.e * deps;
        let excess = trial.abs() - (self.fy + self.hardening * *plastic);
        if excess > 0.0 {
            let dp = excess / (self.e + self.hardening);
            *stress = trial - self.e * dp * trial.signum();
            *plastic += dp;
        } else {
            *stress = trial;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Drives a bar through total strains and returns the stresses.
    fn drive(steel: &HardeningSteel, strains: &[f64]) -> Vec<f64> {
        let (mut p, mut s, mut e) = (0.0, 0.0, 0.0);
        strains
            .iter()
            .map(|&target| {
                // Small increments, as in the explicit solver.
                let n = 200;
                let de = (target - e) / n as f64;
                for _ in 0..n {
                    steel.update(&mut p, de, &mut s);
                }
                e = target;
                s
            })
            .collect()
    }

    #[test]
    fn yields_at_fy_and_hardens_with_the_tangent_modulus() {
        let st = HardeningSteel::thesis(354e6);
        let ey = st.fy / st.e;
        let s = drive(&st, &[0.5 * ey, ey, 0.01, 0.02]);
        // Elastic before yield, at fy exactly at the yield strain.
        assert!((s[0] - 0.5 * st.fy).abs() < 1e-6 * st.fy);
        assert!((s[1] - st.fy).abs() < 1e-6 * st.fy);
        // Independent expectation: fy + Et (eps - eps_y), Et = E H / (E + H).
        let et = 200e9 * 2e9 / 202e9;
        for (k, eps) in [(2, 0.01), (3, 0.02)] {
            let expect = st.fy + et * (eps - ey);
            assert!(
                (s[k] - expect).abs() < 1e-6 * st.fy,
                "{} vs {}",
                s[k],
                expect
            );
        }
        let slope = (s[3] - s[2]) / 0.01;
        assert!((slope - et).abs() < 1e-6 * et);
    }

    #[test]
    fn unloads_elastically_and_reverses_at_the_flow_stress() {
        let st = HardeningSteel::thesis(462e6);
        let ey = st.fy / st.e;
        let e1 = 0.02;
        let s = drive(
            &st,
            &[e1, e1 - 0.5 * ey, e1 - 2.0 * ey, e1 - 2.0 * ey - 0.01],
        );
        let flow = s[0];
        // Unloading with E.
        assert!((s[1] - (flow - st.e * 0.5 * ey)).abs() < 1e-6 * st.fy);
        // Isotropic hardening: reverse yield at -flow, not at flow - 2 fy.
        assert!((s[2] - (flow - st.e * 2.0 * ey)).abs() < 1e-6 * st.fy);
        assert!(s[2] > -flow);
        let reverse_yield_strain = e1 - 2.0 * flow / st.e;
        let expect = -flow - st.tangent_modulus() * (reverse_yield_strain - (e1 - 2.0 * ey - 0.01));
        assert!(
            (s[3] - expect).abs() < 1e-6 * st.fy,
            "{} vs {}",
            s[3],
            expect
        );
    }

    #[test]
    fn dissipation_is_never_negative() {
        let st = HardeningSteel::thesis(328e6);
        let (mut p, mut s) = (0.0, 0.0);
        let mut work = 0.0;
        for k in 0..4000 {
            let de = 2e-5 * ((k as f64) * 0.004).sin().signum();
            let old = s;
            st.update(&mut p, de, &mut s);
            work += 0.5 * (old + s) * de;
            let stored = s * s / (2.0 * st.e);
            assert!(work - stored >= -1e-9 * st.fy, "step {k}");
        }
        assert!(p > 0.0);
    }
}
