//! Concrete damaged plasticity (thesis 2.2.1; issue 8).
//!
//! The model of ABAQUS's "concrete damaged plasticity", which the thesis
//! uses: plasticity in effective stress after Lubliner, Oliver, Oller and
//! Oñate (1989, "A plastic-damage model for concrete", Int. J. Solids
//! Struct. 25(3)) with the two hardening variables of Lee and Fenves (1998,
//! "Plastic-damage model for cyclic loading of concrete structures",
//! J. Eng. Mech. 124(8)), and scalar degradation with stiffness recovery on
//! load reversal:
//!
//! * stress `sigma = (1 - d) sigma_bar`, effective stress
//!   `sigma_bar = D0 : (eps - eps_p)`;
//! * yield surface (Lubliner 1989 eq. 31, Lee and Fenves 1998 eq. 21)
//!   `F = [q - 3 alpha p + beta <s_max> - gamma <-s_max>] / (1 - alpha) - c(kc)`
//!   with `p = -I1/3`, `s_max` the largest principal effective stress,
//!   `alpha = (fb0/fc0 - 1) / (2 fb0/fc0 - 1)` (thesis: `fb0/fc0 = 1.16`),
//!   `gamma = 3 (1 - Kc) / (2 Kc - 1)` (`Kc = 2/3`),
//!   `beta = c_c/c_t (1 - alpha) - (1 + alpha)`, `c_c`, `c_t` the effective
//!   uniaxial compressive and tensile yield stresses;
//! * non-associated hyperbolic Drucker-Prager potential
//!   `G = sqrt((e f_t tan psi)^2 + q^2) - p tan psi`, dilation angle
//!   `psi = 36 deg`, eccentricity `e = 0.1` (thesis 2.2.1);
//! * hardening variables (Lee and Fenves 1998 eq. 13, as ABAQUS):
//!   `dkt = r deps_p,max`, `dkc = -(1 - r) deps_p,min`, `r` the tensile
//!   weight `sum <s_i> / sum |s_i|` of the principal effective stresses;
//! * damage `1 - d = (1 - s_t d_c)(1 - s_c d_t)`, `s_t = 1 - w_t r`,
//!   `s_c = 1 - w_c (1 - r)` with `w_t = 0` and `w_c = 0.95` (thesis 2.2.1:
//!   no tensile stiffness recovered after crushing, 95% of the compressive
//!   stiffness recovered when cracks close); no viscosity.
//!
//! Uniaxial laws:
//!
//! * compression after Vecchio and Collins (1986, "The modified compression
//!   field theory for reinforced concrete elements subjected to shear",
//!   ACI J. 83(2)): the parabola `sigma = f_c (2 eta - eta^2)`,
//!   `eta = eps / eps_c0`, descending to zero at `2 eps_c0`; elastic (slope
//!   `E`) up to `0.3 f_c`, as thesis 2.2.1 describes. `eps_c0` is the strain
//!   at which the parabola passes through `(0.3 f_c / E, 0.3 f_c)`:
//!   `eps_c0 = 0.3 f_c / (E (1 - sqrt(0.7))) = 1.837 f_c / E` (0.00208 for
//!   TP-91), so the curve is continuous and peaks at `f_c`;
//! * tension: elastic up to `f_t`, then Greene's tension stiffening
//!   (Greene 2006, PhD thesis, University of Missouri-Rolla; the law of
//!   Belarbi and Hsu 1994 that Greene and Belarbi use)
//!   `sigma = f_t (eps_cr / eps)^0.4`, `eps_cr = f_t / E`. The thesis calls
//!   it "exponential"; it is a power law in strain. It is a smeared law of
//!   reinforced concrete (bond between cracks), given in strain as the
//!   thesis's ABAQUS input is ("post cracking stress and cracking strain"),
//!   so it is not regularised by the element length;
//! * `f_t = 0.1 f_c`: thesis 2.2.1 gives 0.1 as "the ratio of the uniaxial
//!   tensile stress at failure to the uniaxial compressive stress at
//!   failure".
//!
//! Damage: zero on the ascending branches; on the softening branches the
//! whole drop of stress is damage, `d = 1 - sigma / f_peak`, so the
//! effective stress is perfectly plastic there (`c_t = f_t` always,
//! `c_c = f_c` after the peak) and the return mapping never meets
//! softening (the argument of Lee and Fenves 1998 for putting softening in
//! the damage). Damage is capped at [`MAX_DAMAGE`].
//!
//! Return mapping: backward Euler in effective stress. The flow direction
//! keeps the principal axes of the trial stress and scales its deviator,
//! so the update reduces to one equation `F = 0` in one unknown: the
//! deviator's drop `q_tr - q`, from which the multiplier `dlambda` follows
//! in closed form (for a purely hydrostatic trial, `dlambda` itself). It
//! is solved with a bracket (from the root of the linearised `F`, secant
//! extrapolation, then Illinois false position). The loops are bounded
//! ([`MAX_ITERATIONS`]); if the root is not reached within the tolerance the
//! update takes the bracket end that lies inside the yield surface
//! (`F <= 0`), so the stress is always admissible and finite.

use super::material::{Isotropic, SolidMaterial, Sym6};
use super::simd::{Real, F4, LANES};

/// Largest damage: the stress keeps 1% of the effective stress, so the
/// effective stress can always be recovered from the stress.
pub const MAX_DAMAGE: f64 = 0.99;

/// Iteration limit of each loop of the return mapping.
pub const MAX_ITERATIONS: usize = 100;

/// Parameters of concrete damaged plasticity; [`ConcreteParams::thesis`]
/// gives the values of thesis 2.2.1.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConcreteParams {
    /// Undamaged elasticity and density.
    pub elastic: Isotropic,
    /// Cylinder strength `f_c`, Pa.
    pub fc: f64,
    /// Uniaxial tensile strength `f_t`, Pa.
    pub ft: f64,
    /// Fraction of `f_c` up to which compression is elastic.
    pub elastic_limit: f64,
    /// Exponent of the tension stiffening law.
    pub stiffening_exponent: f64,
    /// Equibiaxial to uniaxial compressive strength `fb0/fc0`.
    pub biaxial_ratio: f64,
    /// Ratio `Kc` of the tensile to the compressive meridian.
    pub kc: f64,
    /// Dilation angle, degrees.
    pub dilation_deg: f64,
    /// Eccentricity of the flow potential.
    pub eccentricity: f64,
    /// Tensile stiffness recovery `w_t` (after crushing).
    pub w_t: f64,
    /// Compressive stiffness recovery `w_c` (after cracking).
    pub w_c: f64,
}

impl ConcreteParams {
    /// Thesis 2.2.1 for a concrete of cylinder strength `fc` (Pa):
    /// `f_t = 0.1 f_c`, elastic to `0.3 f_c`, stiffening exponent 0.4,
    /// `fb0/fc0 = 1.16`, `Kc = 2/3`, `psi = 36 deg`, `e = 0.1`, `w_t = 0`,
    /// `w_c = 0.95`.
    pub fn thesis(elastic: Isotropic, fc: f64) -> Self {
        ConcreteParams {
            elastic,
            fc,
            ft: 0.1 * fc,
            elastic_limit: 0.3,
            stiffening_exponent: 0.4,
            biaxial_ratio: 1.16,
            kc: 2.0 / 3.0,
            dilation_deg: 36.0,
            eccentricity: 0.1,
            w_t: 0.0,
            w_c: 0.95,
        }
    }
}

/// History of one element.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CdpState {
    /// Tensile equivalent plastic strain `kt`.
    pub kappa_t: f64,
    /// Compressive equivalent plastic strain `kc`.
    pub kappa_c: f64,
    /// Tensile damage `d_t(kt)`, kept so that elastic steps need not
    /// evaluate it.
    pub damage_t: f64,
    /// Compressive damage `d_c(kc)`, likewise.
    pub damage_c: f64,
    /// Damage `d` applied to the current stress (recovers the effective
    /// stress, which the solver rotates as part of the stress).
    pub damage: f64,
}

/// Concrete damaged plasticity as a [`SolidMaterial`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConcreteDamagedPlasticity {
    params: ConcreteParams,
    lambda: f64,
    mu: f64,
    bulk: f64,
    alpha: f64,
    /// `(1 - alpha) / f_t`, so that `beta = c_c beta_scale - (1 + alpha)`.
    beta_scale: f64,
    /// `1 / (1 - alpha)`.
    meridian_scale: f64,
    gamma: f64,
    tan_psi: f64,
    /// `e f_t tan psi`, the hyperbola's offset.
    hyper: f64,
    /// Strain at the compressive peak, `eps_c0`.
    eps_c0: f64,
    /// Compressive plastic strain at the peak.
    kappa_peak: f64,
    /// Cracking strain `f_t / E`.
    eps_cr: f64,
    /// Whether `beta >= 0` for every cohesion (`c_c >= elastic_limit f_c`),
    /// so that `F` grows with the largest principal stress.
    beta_nonnegative: bool,
}

impl ConcreteDamagedPlasticity {
    /// The material with parameters `params`.
    ///
    /// # Panics
    /// If `elastic_limit` is not in `(0, 1)`, `Kc` not in `(1/2, 1]`, or
    /// the strengths are not positive.
    pub fn new(params: ConcreteParams) -> Self {
        let p = &params;
        assert!(p.fc > 0.0 && p.ft > 0.0, "strengths must be positive");
        assert!(
            p.elastic_limit > 0.0 && p.elastic_limit < 1.0,
            "elastic limit must be in (0, 1)"
        );
        assert!(p.kc > 0.5 && p.kc <= 1.0, "Kc must be in (1/2, 1]");
        let (lambda, mu) = p.elastic.lame();
        let e = p.elastic.e;
        let eta_limit = 1.0 - (1.0 - p.elastic_limit).sqrt();
        let eps_c0 = p.elastic_limit * p.fc / (e * eta_limit);
        let tan_psi = p.dilation_deg.to_radians().tan();
        let alpha = (p.biaxial_ratio - 1.0) / (2.0 * p.biaxial_ratio - 1.0);
        let beta_min = p.elastic_limit * p.fc / p.ft * (1.0 - alpha) - (1.0 + alpha);
        ConcreteDamagedPlasticity {
            params,
            lambda,
            mu,
            bulk: lambda + 2.0 * mu / 3.0,
            alpha,
            beta_scale: (1.0 - alpha) / p.ft,
            meridian_scale: 1.0 / (1.0 - alpha),
            gamma: 3.0 * (1.0 - p.kc) / (2.0 * p.kc - 1.0),
            tan_psi,
            hyper: p.eccentricity * p.ft * tan_psi,
            eps_c0,
            kappa_peak: eps_c0 - p.fc / e,
            eps_cr: p.ft / e,
            beta_nonnegative: beta_min >= 0.0,
        }
    }

    /// The parameters.
    pub fn params(&self) -> &ConcreteParams {
        &self.params
    }

    /// Strain at the compressive peak `eps_c0`.
    pub fn peak_strain(&self) -> f64 {
        self.eps_c0
    }

    /// Effective compressive yield stress `c_c(kc)`: the ascending
    /// Vecchio-Collins parabola in terms of the plastic strain
    /// `kc = eps - sigma / E`, then `f_c`.
    pub fn compressive_cohesion<T: Real>(&self, kappa_c: T) -> T {
        let fc = self.params.fc;
        // kc = a eta^2 + b eta with a = f_c / E, b = eps_c0 - 2 a < 0.
        let a = fc / self.params.elastic.e;
        let b = self.eps_c0 - 2.0 * a;
        let root = (kappa_c.max(T::splat(0.0)) * (4.0 * a) + b * b).sqrt();
        let eta = (T::splat(-b) + root) / (2.0 * a);
        let ascending = eta * fc * (T::splat(2.0) - eta);
        T::select(
            kappa_c.ge(T::splat(self.kappa_peak)),
            T::splat(fc),
            ascending,
        )
    }

    /// Compressive damage `d_c(kc) = 1 - sigma/f_c` on the descending
    /// parabola, `(eta - 1)^2` with `eta = (kc + f_c/E) / eps_c0`.
    pub fn compressive_damage(&self, kappa_c: f64) -> f64 {
        if kappa_c <= self.kappa_peak {
            return 0.0;
        }
        let eta = (kappa_c + self.params.fc / self.params.elastic.e) / self.eps_c0;
        ((eta - 1.0) * (eta - 1.0)).min(MAX_DAMAGE)
    }

    /// Tensile damage `d_t(kt) = 1 - (eps_cr / (eps_cr + kt))^n`.
    pub fn tensile_damage(&self, kappa_t: f64) -> f64 {
        let ratio = self.eps_cr / (self.eps_cr + kappa_t.max(0.0));
        (1.0 - ratio.powf(self.params.stiffening_exponent)).min(MAX_DAMAGE)
    }

    /// Total damage from the tensile and compressive damage and the
    /// tensile weight `r` of the effective stress.
    fn damage<T: Real>(&self, damage_t: T, damage_c: T, r: T) -> T {
        let one = T::splat(1.0);
        let s_t = one - r * self.params.w_t;
        let s_c = one - (one - r) * self.params.w_c;
        let keep = (one - s_t * damage_c) * (one - s_c * damage_t);
        (one - keep).min(T::splat(MAX_DAMAGE))
    }

    /// Yield function for the largest principal effective stress `s_max`,
    /// von Mises stress `q`, first invariant
    /// `i1` and compressive cohesion `c_c`.
    fn yield_function<T: Real>(&self, s_max: T, q: T, i1: T, c_c: T) -> T {
        let beta = c_c * self.beta_scale - (1.0 + self.alpha);
        let tip = T::select(s_max.gt(T::splat(0.0)), beta * s_max, s_max * self.gamma);
        (q + i1 * self.alpha + tip) * self.meridian_scale - c_c
    }

    /// Advances one material point: `stress` (the damaged stress, rotated
    /// to the end of the step) by the strain increment `deps` (tensor shear
    /// components). The point runs as all four lanes of the solver's
    /// batch update, so material-point tests exercise the solver's own path.
    pub fn update_point(&self, state: &mut CdpState, deps: &[f64; 6], stress: &mut [f64; 6]) {
        let mut states = [*state; LANES];
        let d: Sym6 = std::array::from_fn(|i| F4::splat(deps[i]));
        let mut s: Sym6 = std::array::from_fn(|i| F4::splat(stress[i]));
        self.update_lanes(&mut states, &d, &mut s);
        *state = states[0];
        *stress = std::array::from_fn(|i| s[i].0[0]);
    }

    /// Advances four material points: the elastic trial, the bound that
    /// spares most points their principal values, the principal values and
    /// the damage are computed for the four lanes at once; a lane whose
    /// trial lies outside the yield surface gets its own
    /// [`Self::plastic_return`]. Each lane's result is bit for bit that of
    /// the lane alone (test `lanes_are_independent_points`).
    fn update_lanes(&self, state: &mut [CdpState; LANES], deps: &Sym6, stress: &mut Sym6) {
        let lane = |state: &[CdpState; LANES], f: fn(&CdpState) -> f64| {
            F4(std::array::from_fn(|l| f(&state[l])))
        };
        let one = F4::splat(1.0);
        let recover = one / (one - lane(state, |s| s.damage));
        let tr = deps[0] + deps[1] + deps[2];
        let trial: Sym6 = std::array::from_fn(|i| {
            let volumetric = if i < 3 { tr * self.lambda } else { F4::ZERO };
            stress[i] * recover + (deps[i] * (2.0 * self.mu) + volumetric)
        });
        let m_tr = (trial[0] + trial[1] + trial[2]) / 3.0;
        let mut s_tr = trial;
        for v in s_tr.iter_mut().take(3) {
            *v -= m_tr;
        }
        let q_tr = (double_dot(&s_tr, &s_tr) * 1.5).sqrt();
        let c_c = self.compressive_cohesion(lane(state, |s| s.kappa_c));
        let tol = 1e-10 * self.params.fc;
        let i1 = m_tr * 3.0;
        // With beta >= 0, F grows with the largest principal stress, which
        // is at most m + 2q/3: below that bound the step is elastic, and an
        // undamaged point needs no principal values at all.
        let bound = self.yield_function(m_tr + q_tr * 2.0 / 3.0, q_tr, i1, c_c);
        let surely_elastic: [bool; LANES] =
            std::array::from_fn(|l| self.beta_nonnegative && bound.0[l] <= tol);
        let undamaged: [bool; LANES] = std::array::from_fn(|l| {
            surely_elastic[l] && state[l].damage_t == 0.0 && state[l].damage_c == 0.0
        });
        if undamaged.iter().all(|&u| u) {
            *stress = trial;
            for st in state.iter_mut() {
                st.damage = 0.0;
            }
            return;
        }
        let (d_max, d_min) = deviator_extremes(&s_tr);
        let f_tr = self.yield_function(m_tr + d_max, q_tr, i1, c_c);
        let (mut m, mut rho) = (m_tr, one);
        for (l, st) in state.iter_mut().enumerate() {
            if surely_elastic[l] || f_tr.0[l] <= tol {
                continue;
            }
            let trial = Trial {
                m: m_tr.0[l],
                q: q_tr.0[l],
                d_max: d_max.0[l],
                d_min: d_min.0[l],
                c_c: c_c.0[l],
            };
            let ret = self.plastic_return(&trial, st, f_tr.0[l], tol);
            // A hardening variable that did not move keeps its damage.
            if ret.dkt != 0.0 {
                st.kappa_t += ret.dkt;
                st.damage_t = self.tensile_damage(st.kappa_t);
            }
            if ret.dkc != 0.0 {
                st.kappa_c += ret.dkc;
                st.damage_c = self.compressive_damage(st.kappa_c);
            }
            (m.0[l], rho.0[l]) = (ret.m, ret.rho);
        }
        let r = tensile_weight(&principal(m, rho, d_max, d_min));
        let damage = self.damage(lane(state, |s| s.damage_t), lane(state, |s| s.damage_c), r);
        let keep = one - damage;
        for i in 0..6 {
            let mean = if i < 3 { m } else { F4::ZERO };
            let damaged = keep * (rho * s_tr[i] + mean);
            stress[i] = F4::select(undamaged, trial[i], damaged);
        }
        for (l, st) in state.iter_mut().enumerate() {
            st.damage = if undamaged[l] { 0.0 } else { damage.0[l] };
        }
    }

    /// One step of a material-point test: `deps` prescribed except on the
    /// components `free` (normal components, kept equal to each other by
    /// the symmetry of the loading), whose common strain increment is
    /// found so that their stress is zero. The response has a kink at zero
    /// stress (the corner of Lubliner's surface), so the solve brackets the
    /// root and uses Illinois false position, to `1e-8 f_c`. Returns the
    /// strain increment applied, or `None` (state and stress unchanged) if
    /// no bracket or no convergence was found.
    pub fn step_with_free_stress(
        &self,
        state: &mut CdpState,
        stress: &mut [f64; 6],
        deps: [f64; 6],
        free: &[usize],
    ) -> Option<[f64; 6]> {
        let trial = |x: f64| {
            let mut d = deps;
            for &i in free {
                d[i] = x;
            }
            let (mut st, mut s) = (*state, *stress);
            self.update_point(&mut st, &d, &mut s);
            (s[free[0]], st, s, d)
        };
        let nu = self.params.elastic.nu;
        let driven: f64 = (0..3).filter(|i| !free.contains(i)).map(|i| deps[i]).sum();
        let width = 1e-3 * driven.abs().max(1e-9);
        let (mut a, mut b) = (-nu * driven - width, -nu * driven + width);
        let (mut fa, mut fb) = (trial(a).0, trial(b).0);
        for _ in 0..MAX_ITERATIONS {
            if fa < 0.0 && fb > 0.0 {
                break;
            }
            let w = b - a;
            if fa >= 0.0 {
                a -= w;
                fa = trial(a).0;
            }
            if fb <= 0.0 {
                b += w;
                fb = trial(b).0;
            }
        }
        if !(fa < 0.0 && fb > 0.0) {
            return None;
        }
        let mut side = 0;
        for _ in 0..2 * MAX_ITERATIONS {
            let x = (a * fb - b * fa) / (fb - fa);
            let (f, st, s, d) = trial(x);
            if f.abs() < 1e-8 * self.params.fc || b - a <= 1e-15 * b.abs().max(a.abs()) {
                *state = st;
                *stress = s;
                return Some(d);
            }
            if f < 0.0 {
                a = x;
                fa = f;
                if side == -1 {
                    fb *= 0.5;
                }
                side = -1;
            } else {
                b = x;
                fb = f;
                if side == 1 {
                    fa *= 0.5;
                }
                side = 1;
            }
        }
        None
    }

    /// The state after a plastic multiplier `dl` that leaves the deviator
    /// at `q` (`radius = sqrt(h^2 + q^2)`): mean stress, deviator scale,
    /// hardening increments and the yield function there.
    fn at(&self, t: &Trial, state: &CdpState, dl: f64, q: f64, radius: f64) -> Return {
        let m = t.m - self.bulk * dl * self.tan_psi;
        let rho = if t.q > 0.0 { q / t.q } else { 1.0 };
        let s = principal(m, rho, t.d_max, t.d_min);
        let r = tensile_weight(&s);
        let flow = |dev: f64| dl * (1.5 * rho * dev / radius + self.tan_psi / 3.0);
        let dkt = r * flow(t.d_max).max(0.0);
        let dkc = (1.0 - r) * (-flow(t.d_min)).max(0.0);
        let c_c = if dkc == 0.0 {
            t.c_c
        } else {
            self.compressive_cohesion(state.kappa_c + dkc)
        };
        let f = self.yield_function(s[0], q, 3.0 * m, c_c);
        Return {
            m,
            rho,
            dkt,
            dkc,
            f,
        }
    }

    /// The state after the deviator has fallen by `drop` from `q_tr` to
    /// `q = q_tr - drop > 0`. The flow rule's deviatoric part,
    /// `q + 3 mu dl q / sqrt(h^2 + q^2) = q_tr`, gives the multiplier
    /// explicitly, `dl = (q_tr - q) sqrt(h^2 + q^2) / (3 mu q)`, where for a
    /// given multiplier `q` would need an inner iteration
    /// ([`Self::scaled_q`]).
    fn at_drop(&self, t: &Trial, state: &CdpState, drop: f64) -> Return {
        // A drop rounded onto q_tr would need an infinite multiplier.
        let q = (t.q - drop).max(f64::EPSILON * t.q);
        let radius = (self.hyper * self.hyper + q * q).sqrt();
        let dl = (t.q - q) * radius / (3.0 * self.mu * q);
        self.at(t, state, dl, q, radius)
    }

    /// Solves `q + 3 mu dl q / sqrt(h^2 + q^2) = q_tr` for `q` in
    /// `[0, q_tr]`: the left side is increasing and concave in `q`, so
    /// Newton from the left converges monotonically (and stays left).
    /// Needed only for the first point of a return whose linearisation
    /// overshoots the apex.
    fn scaled_q(&self, q_tr: f64, dl: f64) -> f64 {
        if q_tr <= 0.0 || dl <= 0.0 {
            return q_tr;
        }
        let k = 3.0 * self.mu * dl;
        let h2 = self.hyper * self.hyper;
        // The root without the offset (h = 0); with it the left side is
        // smaller there, so this start is left of the root and within
        // about k h^2 / (2 q^2) of it.
        let mut q = (q_tr - k).max(0.0);
        for _ in 0..MAX_ITERATIONS {
            let radius = (h2 + q * q).sqrt();
            let g = q + k * q / radius - q_tr;
            let slope = 1.0 + k * h2 / (radius * radius * radius);
            // max/min, not clamp: a NaN (a diverged run, reported by the solver) must not
            // panic here.
            let next = (q - g / slope).max(0.0).min(q_tr);
            if (next - q).abs() <= 1e-14 * q_tr {
                return next;
            }
            q = next;
        }
        q
    }

    /// The multiplier at which `F` would reach zero if it fell linearly from
    /// `f_tr` at the rate of a surface without hardening and a potential
    /// without the hyperbola's offset (the mean stress falls by
    /// `K tan psi`, `q` by `3 mu` per unit multiplier, and the largest
    /// principal stress by both): exact in that limit, otherwise the first
    /// end of the bracket, close to the root. Measured on TP-91 at 50 mm
    /// (3.3 million returns, 2026-11-23): 2.8 evaluations of `F` per return
    /// with the secant extrapolation of [`find_root`], against 4.6 from
    /// the elastic guess `f_tr / (E (1 + tan psi))` and doubling; 2.95
    /// (6.55 million evaluations) with the deviator's drop as the unknown
    /// (2026-11-29).
    fn first_multiplier(&self, t: &Trial, f_tr: f64) -> f64 {
        let drop_m = self.bulk * self.tan_psi;
        let drop_q = 3.0 * self.mu;
        let tip = if t.m + t.d_max > 0.0 {
            t.c_c * self.beta_scale - (1.0 + self.alpha)
        } else {
            self.gamma
        };
        let rate = if t.q > 0.0 { t.d_max / t.q } else { 0.0 };
        let slope = (drop_q + 3.0 * self.alpha * drop_m + tip * (drop_m + drop_q * rate))
            * self.meridian_scale;
        if slope > 0.0 && slope.is_finite() {
            f_tr / slope
        } else {
            f_tr / (self.params.elastic.e * (1.0 + self.tan_psi))
        }
    }

    /// Finds the return with `F = 0`. With a deviator in the trial stress
    /// the unknown is the deviator's drop `q_tr - q` in `[0, q_tr)`, from
    /// which the multiplier follows without iteration ([`Self::at_drop`]);
    /// for a purely hydrostatic trial it is the multiplier itself (`q`
    /// stays zero). Either grows with the multiplier, so `F` falls with it.
    fn plastic_return(&self, t: &Trial, state: &CdpState, f_tr: f64, tol: f64) -> Return {
        let dl = self.first_multiplier(t, f_tr);
        if t.q > 0.0 {
            // The linearised return drops q by 3 mu dl; past the apex the
            // exact drop for that multiplier.
            let drop = 3.0 * self.mu * dl;
            let first = if drop < t.q {
                drop
            } else {
                t.q - self.scaled_q(t.q, dl)
            };
            find_root(f_tr, tol, first, t.q, |x| self.at_drop(t, state, x))
        } else {
            find_root(f_tr, tol, dl, f64::INFINITY, |x| {
                self.at(t, state, x, 0.0, self.hyper)
            })
        }
    }
}

/// The root of a yield function `F(x)` that falls as `x` grows from 0
/// (where it is `f_tr > 0`) towards `limit`: from `first`, secant
/// extrapolation (at most doubling `x`, at most halving the distance to
/// `limit`) until `F` changes sign or is within `tol`, then Illinois false
/// position on the bracket. Without convergence it returns the admissible
/// end of the bracket (`F <= 0`), or, if no sign change was found within
/// [`MAX_ITERATIONS`] extrapolations, the last point tried.
fn find_root(f_tr: f64, tol: f64, first: f64, limit: f64, eval: impl Fn(f64) -> Return) -> Return {
    let (mut lo, mut f_lo) = (0.0, f_tr);
    let mut hi_x = first;
    let mut hi = eval(hi_x);
    let mut n = 0;
    while hi.f > tol && n < MAX_ITERATIONS {
        // Still short of the root: extrapolate along the secant through
        // the last two points.
        let next = if f_lo > hi.f {
            hi_x + hi.f * (hi_x - lo) / (f_lo - hi.f)
        } else {
            2.0 * hi_x
        };
        lo = hi_x;
        f_lo = hi.f;
        hi_x = next.min(2.0 * hi_x).min(0.5 * (hi_x + limit));
        hi = eval(hi_x);
        n += 1;
    }
    if hi.f > 0.0 || hi.f.abs() <= tol {
        return hi;
    }
    let mut f_hi = hi.f;
    let mut side = 0;
    for _ in 0..MAX_ITERATIONS {
        let x = (lo * f_hi - hi_x * f_lo) / (f_hi - f_lo);
        let x = if x > lo && x < hi_x {
            x
        } else {
            0.5 * (lo + hi_x)
        };
        let mid = eval(x);
        if mid.f.abs() <= tol {
            return mid;
        }
        if mid.f > 0.0 {
            lo = x;
            f_lo = mid.f;
            if side == -1 {
                f_hi *= 0.5;
            }
            side = -1;
        } else {
            hi_x = x;
            hi = mid;
            f_hi = hi.f;
            if side == 1 {
                f_lo *= 0.5;
            }
            side = 1;
        }
        if hi_x - lo <= 1e-15 * hi_x {
            break;
        }
    }
    hi
}

/// The elastic trial of a plastic step, in principal terms.
struct Trial {
    m: f64,
    q: f64,
    d_max: f64,
    d_min: f64,
    /// Compressive cohesion before the step.
    c_c: f64,
}

/// The state at a plastic multiplier.
struct Return {
    m: f64,
    rho: f64,
    dkt: f64,
    dkc: f64,
    f: f64,
}

/// `a : b` for symmetric tensors stored `xx, yy, zz, xy, yz, zx`.
fn double_dot<T: Real>(a: &[T; 6], b: &[T; 6]) -> T {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + (a[3] * b[3] + a[4] * b[4] + a[5] * b[5]) * 2.0
}

/// Largest and smallest principal values of a deviator, from its
/// invariants. The principal values are `R c` with `R = 2 sqrt(J2 / 3)`
/// and `c` the roots of Chebyshev's cubic `4 c^3 - 3 c = cos 3 theta`,
/// `cos 3 theta = (3 sqrt 3 / 2) J3 / J2^(3/2)`: the largest is
/// `cos theta`, the smallest `cos(theta + 2 pi / 3)`.
fn deviator_extremes<T: Real>(s: &[T; 6]) -> (T, T) {
    let zero = T::splat(0.0);
    let j2 = double_dot(s, s) * 0.5;
    let j3 = s[0] * (s[1] * s[2] - s[4] * s[4]) - s[3] * (s[3] * s[2] - s[4] * s[5])
        + s[5] * (s[3] * s[4] - s[1] * s[5]);
    let root = j2.sqrt();
    let radius = root * 2.0 / 3f64.sqrt();
    let cos3 = (j3 * (1.5 * 3f64.sqrt()) / (j2 * root)).clamp(-1.0, 1.0);
    let cos = largest_chebyshev_root(cos3);
    let sin = (T::splat(1.0) - cos * cos).max(zero).sqrt();
    // cos(theta + 2 pi / 3) without a second cosine.
    let third = cos * -0.5 - sin * (0.5 * 3f64.sqrt());
    // A zero (or NaN) deviator has no direction: both are zero.
    let some = j2.gt(zero);
    (
        T::select(some, radius * cos, zero),
        T::select(some, radius * third, zero),
    )
}

/// `cos(acos(x) / 3)` for `x` in `[-1, 1]`: the largest root `c` in
/// `[1/2, 1]` of `4 c^3 - 3 c = x`, without the arc cosine, sine and cosine
/// it would take (a fifth of a material point's work in cracked concrete).
/// With `v = sqrt((1 + x) / 2) = cos(3 theta / 2)`, `c = cos(2/3 acos v)` is
/// smooth and concave in `v`, so the parabola through `(0, 1/2)` with its
/// slope `1/sqrt 3` there and through `(1, 1)` lies above it, by at most
/// 0.0037. The cubic is convex and increasing to the right of the root, so
/// Newton's method from above falls monotonically onto it: three steps
/// leave at most 4e-15 (test `the_chebyshev_root_is_the_cosine_of_a_third_of_the_angle`).
/// A step that would go up (rounding at the root) or is undefined (the
/// double root at `x = -1`, where the start is exact) is not taken.
fn largest_chebyshev_root<T: Real>(x: T) -> T {
    let v = (x * 0.5 + 0.5).sqrt();
    let slope = 1.0 / 3f64.sqrt();
    let mut c = v * (T::splat(slope) - v * (slope - 0.5)) + 0.5;
    for _ in 0..3 {
        let c2 = c * c;
        let step = ((c2 * 4.0 - 3.0) * c - x) / (c2 * 12.0 - 3.0);
        c = T::select(step.gt(T::splat(0.0)), c - step, c);
    }
    c
}

/// Principal values `m + rho d_i` of a stress whose deviator has the
/// extreme principal values `d_max`, `d_min` (the middle one is
/// `-(d_max + d_min)`), scaled by `rho`, plus the mean `m`.
fn principal<T: Real>(m: T, rho: T, d_max: T, d_min: T) -> [T; 3] {
    [m + rho * d_max, m - rho * (d_max + d_min), m + rho * d_min]
}

/// Tensile weight `r = sum <s_i> / sum |s_i|` of principal stresses
/// (Lee and Fenves 1998 eq. 15); zero for a zero stress.
fn tensile_weight<T: Real>(s: &[T; 3]) -> T {
    let zero = T::splat(0.0);
    let total = s[0].abs() + s[1].abs() + s[2].abs();
    let tension = s[0].max(zero) + s[1].max(zero) + s[2].max(zero);
    T::select(total.gt(zero), tension / total, zero)
}

impl SolidMaterial for ConcreteDamagedPlasticity {
    type State = CdpState;

    fn initial(&self) -> Isotropic {
        self.params.elastic
    }

    fn update(&self, state: &mut [CdpState; LANES], deps: &Sym6, _h: F4, stress: &mut Sym6) {
        self.update_lanes(state, deps, stress);
    }

    fn retained_stiffness(&self, state: &[CdpState; LANES]) -> F4 {
        F4(std::array::from_fn(|l| 1.0 - state[l].damage))
    }

    fn field_names(&self) -> &'static [&'static str] {
        &["tension_damage", "compression_damage", "damage"]
    }

    fn fields(&self, state: &CdpState, out: &mut Vec<f64>) {
        out.push(state.damage_t);
        out.push(state.damage_c);
        out.push(state.damage);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const FC: f64 = 28.3e6;

    /// TP-91's concrete: `f_c = 28.3 MPa`, `E = 4700 sqrt(f_c)` (ACI 318).
    fn tp91() -> ConcreteDamagedPlasticity {
        let elastic = Isotropic {
            e: 4700.0 * 28.3f64.sqrt() * 1e6,
            nu: 0.2,
            density: 2400.0,
        };
        ConcreteDamagedPlasticity::new(ConcreteParams::thesis(elastic, FC))
    }

    /// A material point driven by strain increments, with some stress
    /// components held at zero, and its energy account.
    #[derive(Clone, Copy, Default)]
    struct Point {
        state: CdpState,
        stress: [f64; 6],
        strain: [f64; 6],
        work: f64,
    }

    impl Point {
        fn step(&mut self, mat: &ConcreteDamagedPlasticity, deps: &[f64; 6]) {
            let old = self.stress;
            mat.update_point(&mut self.state, deps, &mut self.stress);
            let mid: [f64; 6] = std::array::from_fn(|i| 0.5 * (old[i] + self.stress[i]));
            self.work += double_dot(&mid, deps);
            for i in 0..6 {
                self.strain[i] += deps[i];
            }
        }

        /// One step with the stress on `free` held at zero.
        fn mixed(&mut self, mat: &ConcreteDamagedPlasticity, deps: [f64; 6], free: &[usize]) {
            let mut p = *self;
            let d = mat
                .step_with_free_stress(&mut p.state, &mut p.stress, deps, free)
                .unwrap_or_else(|| panic!("no zero-stress step at strain {:?}", self.strain));
            let mid: [f64; 6] = std::array::from_fn(|i| 0.5 * (self.stress[i] + p.stress[i]));
            p.work += double_dot(&mid, &d);
            for i in 0..6 {
                p.strain[i] += d[i];
            }
            *self = p;
        }

        /// Stored energy `(1 - d) psi0(sigma_bar) = sigma : C0^-1 : sigma / (2 (1 - d))`.
        fn stored(&self, mat: &ConcreteDamagedPlasticity) -> f64 {
            let Isotropic { e, nu, .. } = mat.params().elastic;
            let s = &self.stress;
            let tr = s[0] + s[1] + s[2];
            let energy = ((1.0 + nu) * double_dot(s, s) - nu * tr * tr) / e;
            energy / (2.0 * (1.0 - self.state.damage))
        }

        fn dissipation(&self, mat: &ConcreteDamagedPlasticity) -> f64 {
            self.work - self.stored(mat)
        }
    }

    /// Uniaxial stress along x: `steps` equal increments to `target`.
    fn uniaxial(
        mat: &ConcreteDamagedPlasticity,
        p: &mut Point,
        target: f64,
        steps: usize,
    ) -> Vec<(f64, f64)> {
        let de = (target - p.strain[0]) / steps as f64;
        (0..steps)
            .map(|_| {
                p.mixed(mat, [de, 0.0, 0.0, 0.0, 0.0, 0.0], &[1, 2]);
                (p.strain[0], p.stress[0])
            })
            .collect()
    }

    #[test]
    fn uniaxial_tension_is_elastic_then_follows_greenes_stiffening() {
        let mat = tp91();
        let e = mat.params().elastic.e;
        let ft = 0.1 * FC;
        let eps_cr = ft / e;
        let mut p = Point::default();
        let curve = uniaxial(&mat, &mut p, 20.0 * eps_cr, 2000);
        let mut worst: f64 = 0.0;
        for &(eps, sig) in &curve {
            // Independent expectation: E eps, then f_t (eps_cr / eps)^0.4.
            let expect = if eps <= eps_cr {
                e * eps
            } else {
                ft * (eps_cr / eps).powf(0.4)
            };
            worst = worst.max((sig - expect).abs() / ft);
        }
        eprintln!("uniaxial tension: worst |error| / f_t = {worst:.2e}");
        assert!(worst < 1e-6, "{worst}");
        let (eps_end, sig_end) = *curve.last().unwrap();
        eprintln!(
            "  at {:.1} eps_cr: {:.4} MPa (f_t {:.4} MPa)",
            eps_end / eps_cr,
            sig_end / 1e6,
            ft / 1e6
        );
        assert!((sig_end - ft * 20f64.powf(-0.4)).abs() < 1e-6 * ft);
        // Lateral stresses are zero, so the point is in uniaxial stress.
        assert!(p.stress[1].abs() < 1e-5 * FC && p.stress[2].abs() < 1e-5 * FC);
    }

    #[test]
    fn uniaxial_compression_follows_vecchio_collins() {
        let mat = tp91();
        let e = mat.params().elastic.e;
        let eps0 = mat.peak_strain();
        // eps_c0 = 0.3 f_c / (E (1 - sqrt 0.7)).
        assert!((eps0 - 0.3 * FC / (e * (1.0 - 0.7f64.sqrt()))).abs() < 1e-12);
        let mut p = Point::default();
        let curve = uniaxial(&mat, &mut p, -1.9 * eps0, 3800);
        let mut worst: f64 = 0.0;
        let (mut peak, mut peak_eps) = (0.0, 0.0);
        for &(eps, sig) in &curve {
            let (c, eta) = (-sig, -eps / eps0);
            let expect = if c <= 0.3 * FC + 1.0 && -eps * e <= 0.3 * FC {
                -eps * e
            } else {
                FC * (2.0 * eta - eta * eta)
            };
            worst = worst.max((c - expect).abs() / FC);
            if c > peak {
                peak = c;
                peak_eps = -eps;
            }
        }
        eprintln!(
            "uniaxial compression: worst |error| / f_c = {worst:.2e}; peak {:.4} MPa at {:.6} (eps_c0 {:.6})",
            peak / 1e6,
            peak_eps,
            eps0
        );
        assert!(worst < 1e-6, "{worst}");
        assert!((peak - FC).abs() < 1e-6 * FC);
        assert!((peak_eps - eps0).abs() < 0.001 * eps0);
    }

    #[test]
    fn equibiaxial_compression_strength_is_116_percent() {
        let mat = tp91();
        let eps0 = mat.peak_strain();
        let steps = 2000;
        let de = -1.5 * eps0 / steps as f64;
        let mut p = Point::default();
        let mut biaxial: f64 = 0.0;
        for _ in 0..steps {
            p.mixed(&mat, [de, de, 0.0, 0.0, 0.0, 0.0], &[2]);
            assert!((p.stress[0] - p.stress[1]).abs() < 1e-6 * FC);
            biaxial = biaxial.max(-p.stress[0]);
        }
        let mut q = Point::default();
        let uni = uniaxial(&mat, &mut q, -1.5 * eps0, steps)
            .iter()
            .fold(0.0f64, |m, &(_, s)| m.max(-s));
        eprintln!(
            "equibiaxial {:.4} MPa / uniaxial {:.4} MPa = {:.5}",
            biaxial / 1e6,
            uni / 1e6,
            biaxial / uni
        );
        assert!((biaxial / uni - 1.16).abs() < 1e-4);
    }

    #[test]
    fn pure_shear_cracks_at_the_lubliner_surface() {
        let mat = tp91();
        let ft = 0.1 * FC;
        // Independent expectation from Lubliner's surface in pure shear
        // (principal stresses tau, 0, -tau; q = sqrt(3) tau, I1 = 0) with
        // the initial cohesion c_c = 0.3 f_c:
        // tau_cr = (1 - alpha) c_c / (sqrt 3 + beta).
        let alpha = 0.16 / 1.32;
        let c0 = 0.3 * FC;
        let beta = c0 / ft * (1.0 - alpha) - (1.0 + alpha);
        let tau_cr = (1.0 - alpha) * c0 / (3f64.sqrt() + beta);
        let mu = mat.params().elastic.shear_modulus();
        let mut p = Point::default();
        let dg = tau_cr / (2.0 * mu) / 1000.0;
        let mut first = None;
        let mut peak: f64 = 0.0;
        for _ in 0..3000 {
            p.step(&mat, &[0.0, 0.0, 0.0, dg, 0.0, 0.0]);
            peak = peak.max(p.stress[3]);
            if first.is_none() && p.state.kappa_t > 0.0 {
                first = Some(p.stress[3]);
            }
        }
        let first = first.expect("cracks");
        eprintln!(
            "pure shear: cracking tau {:.4} MPa (closed form {:.4}, = {:.3} f_t), peak {:.4} MPa, d = {:.3}",
            first / 1e6,
            tau_cr / 1e6,
            tau_cr / ft,
            peak / 1e6,
            p.state.damage
        );
        assert!((first - tau_cr).abs() < 2e-3 * tau_cr);
        // With the normal strains held, dilatancy builds up confinement
        // and the shear stress rises past cracking.
        assert!(peak > tau_cr);
        assert!(p.state.damage > 0.0 && p.dissipation(&mat) > 0.0);
    }

    #[test]
    fn cracked_concrete_recovers_compressive_stiffness() {
        let mat = tp91();
        let e = mat.params().elastic.e;
        let eps_cr = 0.1 * FC / e;
        let mut p = Point::default();
        uniaxial(&mat, &mut p, 10.0 * eps_cr, 1000);
        let dt = mat.tensile_damage(p.state.kappa_t);
        // Unload, then into compression: the slope on the way back to zero
        // stress (at 9 eps_cr) is the cracked (1 - d_t) E; in compression
        // 1 - 0.05 d_t.
        let back = uniaxial(&mat, &mut p, 9.5 * eps_cr, 100);
        let k_open = (back[99].1 - back[49].1) / (back[99].0 - back[49].0);
        let plastic = p.strain[0] - p.stress[0] / k_open;
        uniaxial(&mat, &mut p, plastic, 200);
        let comp = uniaxial(&mat, &mut p, plastic - 0.1 * FC / e, 200);
        let k_closed = (comp[199].1 - comp[99].1) / (comp[199].0 - comp[99].0);
        eprintln!(
            "tension -> compression: d_t = {dt:.4}; open {:.4} E (expect {:.4}), closed {:.4} E (expect {:.4})",
            k_open / e,
            1.0 - dt,
            k_closed / e,
            1.0 - 0.05 * dt
        );
        assert!(dt > 0.5);
        assert!((k_open / e - (1.0 - dt)).abs() < 1e-6);
        assert!((k_closed / e - (1.0 - 0.05 * dt)).abs() < 1e-6);
    }

    #[test]
    fn crushed_concrete_does_not_recover_tensile_stiffness() {
        let mat = tp91();
        let e = mat.params().elastic.e;
        let eps0 = mat.peak_strain();
        let mut p = Point::default();
        uniaxial(&mat, &mut p, -1.5 * eps0, 1500);
        let dc = mat.compressive_damage(p.state.kappa_c);
        // Unload to zero stress along (1 - d_c) E, then pull into tension
        // (below f_t): the same slope, w_t = 0.
        let back = uniaxial(&mat, &mut p, -1.4 * eps0, 100);
        let k_comp = (back[99].1 - back[49].1) / (back[99].0 - back[49].0);
        let plastic = p.strain[0] - p.stress[0] / k_comp;
        uniaxial(&mat, &mut p, plastic, 200);
        let ten = uniaxial(&mat, &mut p, plastic + 0.02 * FC / e, 100);
        let k_tens = (ten[99].1 - ten[49].1) / (ten[99].0 - ten[49].0);
        eprintln!(
            "compression -> tension: d_c = {dc:.4} (expect 0.25); compression {:.4} E, tension {:.4} E (expect {:.4})",
            k_comp / e,
            k_tens / e,
            1.0 - dc
        );
        assert!((dc - 0.25).abs() < 1e-3);
        assert!((k_comp / e - (1.0 - dc)).abs() < 1e-6);
        assert!((k_tens / e - (1.0 - dc)).abs() < 1e-6);
    }

    #[test]
    fn dissipation_is_never_negative() {
        let mat = tp91();
        let eps0 = mat.peak_strain();
        let eps_cr = 0.1 * FC / mat.params().elastic.e;
        let scale = FC * eps_cr;
        // Uniaxial cycles: tension, crack closure, crushing, tension again.
        // A step in which the stress changes sign switches the damage
        // (stiffness recovery) at its end, which the trapezoidal work
        // misses by a second-order amount: the lowest step is allowed
        // -1e-5 f_c eps_cr.
        let mut p = Point::default();
        let mut last = 0.0;
        let mut lowest_step = f64::INFINITY;
        for target in [
            5.0 * eps_cr,
            -0.5 * eps0,
            8.0 * eps_cr,
            -1.6 * eps0,
            12.0 * eps_cr,
        ] {
            let n = 400;
            let de = (target - p.strain[0]) / n as f64;
            for _ in 0..n {
                p.mixed(&mat, [de, 0.0, 0.0, 0.0, 0.0, 0.0], &[1, 2]);
                let d = p.dissipation(&mat);
                assert!(d >= -1e-9 * scale);
                lowest_step = lowest_step.min(d - last);
                last = d;
            }
        }
        eprintln!(
            "uniaxial cycles: dissipation {:.1} J/m^3, lowest step {:.2e} J/m^3",
            last, lowest_step
        );
        assert!(lowest_step > -1e-5 * scale);
        // Cyclic shear strain, the other strains held at zero. In mixed
        // states the damage depends on the tensile weight r of the stress
        // (stiffness recovery, w_c), so an elastic step that closes cracks
        // (r falls) lowers d and returns stored energy, psi0 * dd < 0: a
        // property of the ABAQUS form, not of the integration. The total
        // stays positive, and such steps are elastic.
        let mut p = Point::default();
        let mut last = 0.0;
        let mut returned = 0.0;
        for target in [4.0 * eps_cr, -4.0 * eps_cr, 8.0 * eps_cr] {
            let n = 400;
            let de = (target - p.strain[3]) / n as f64;
            for _ in 0..n {
                let before = p.state;
                p.step(&mat, &[0.0, 0.0, 0.0, de, 0.0, 0.0]);
                let d = p.dissipation(&mat);
                assert!(d >= -1e-9 * scale);
                if d - last < -1e-9 * scale {
                    assert_eq!(
                        (before.kappa_t, before.kappa_c),
                        (p.state.kappa_t, p.state.kappa_c)
                    );
                    assert!(p.state.damage < before.damage);
                    returned -= d - last;
                }
                last = d;
            }
        }
        eprintln!(
            "cyclic shear: dissipation {:.1} J/m^3, returned by elastic recovery {:.1} J/m^3",
            last, returned
        );
        assert!(returned < 0.02 * last);
    }

    #[test]
    fn large_and_degenerate_increments_stay_finite_and_admissible() {
        let mat = tp91();
        let cases: [[f64; 6]; 5] = [
            [0.05, 0.0, 0.0, 0.0, 0.0, 0.0],
            [-0.05, -0.05, -0.05, 0.0, 0.0, 0.0],
            [0.05, 0.05, 0.05, 0.0, 0.0, 0.0],
            [0.0, 0.0, 0.0, 0.03, -0.02, 0.01],
            [-0.02, 0.01, 0.0, 0.0, 0.04, 0.0],
        ];
        for deps in cases {
            let mut p = Point::default();
            for _ in 0..5 {
                p.step(&mat, &deps);
                assert!(p.stress.iter().all(|s| s.is_finite()), "{deps:?}");
                let keep = 1.0 - p.state.damage;
                let bar: [f64; 6] = std::array::from_fn(|i| p.stress[i] / keep);
                let m = (bar[0] + bar[1] + bar[2]) / 3.0;
                let mut s = bar;
                for v in s.iter_mut().take(3) {
                    *v -= m;
                }
                let (d_max, _) = deviator_extremes(&s);
                let q = (1.5 * double_dot(&s, &s)).sqrt();
                let f = mat.yield_function(
                    m + d_max,
                    q,
                    3.0 * m,
                    mat.compressive_cohesion(p.state.kappa_c),
                );
                assert!(f <= 1e-8 * FC, "{deps:?}: F = {f}");
            }
        }
    }

    #[test]
    fn the_scaled_deviator_solves_its_equation_to_the_tolerance() {
        // Against bisection of q + k q / sqrt(h^2 + q^2) = q_tr, from far
        // above the hyperbola's offset h to well below it.
        let mat = tp91();
        let h = mat.hyper;
        for q_tr in [0.01 * h, 0.5 * h, 2.0 * h, 20.0 * h, 500.0 * h] {
            for share in [1e-9, 1e-4, 0.01, 0.3, 0.9, 0.999, 3.0] {
                let dl = share * q_tr / (3.0 * mat.mu);
                let k = 3.0 * mat.mu * dl;
                let g = |q: f64| q + k * q / (h * h + q * q).sqrt() - q_tr;
                let (mut lo, mut hi) = (0.0, q_tr);
                for _ in 0..200 {
                    let mid = 0.5 * (lo + hi);
                    if g(mid) > 0.0 {
                        hi = mid;
                    } else {
                        lo = mid;
                    }
                }
                let q = mat.scaled_q(q_tr, dl);
                assert!(
                    (q - lo).abs() <= 2e-14 * q_tr,
                    "q_tr = {q_tr}, k = {k}: {q} against {lo}"
                );
            }
        }
    }

    #[test]
    fn the_chebyshev_root_is_the_cosine_of_a_third_of_the_angle() {
        for i in 0..=20_000 {
            let x = -1.0 + i as f64 / 10_000.0;
            let c = largest_chebyshev_root(x);
            let exact = (x.acos() / 3.0).cos();
            assert!((c - exact).abs() <= 4e-15, "x = {x}: {c} against {exact}");
        }
        assert!(largest_chebyshev_root(f64::NAN).is_nan());
    }

    #[test]
    fn deviator_extremes_are_the_principal_values() {
        // Known principal values, rotated by a rotation about a skew axis:
        // distinct, two equal (either way round), and zero.
        let (axis, angle) = ([1.0, 2.0, -2.0].map(|v: f64| v / 3.0), 0.7f64);
        let (sn, cs) = angle.sin_cos();
        let k = [
            [0.0, -axis[2], axis[1]],
            [axis[2], 0.0, -axis[0]],
            [-axis[1], axis[0], 0.0],
        ];
        let rot: [[f64; 3]; 3] = std::array::from_fn(|i| {
            std::array::from_fn(|j| {
                let kk: f64 = (0..3).map(|l| k[i][l] * k[l][j]).sum();
                f64::from(u8::from(i == j)) + sn * k[i][j] + (1.0 - cs) * kk
            })
        });
        for d in [
            [3.0, -1.0, -2.0],
            [1.0, 1.0, -2.0],
            [2.0, -1.0, -1.0],
            [0.5, 0.0, -0.5],
        ] {
            let a: [[f64; 3]; 3] = std::array::from_fn(|i| {
                std::array::from_fn(|j| (0..3).map(|l| rot[i][l] * d[l] * rot[j][l]).sum())
            });
            let s = [a[0][0], a[1][1], a[2][2], a[0][1], a[1][2], a[2][0]];
            let (hi, lo) = deviator_extremes(&s);
            let scale = d.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let (want_hi, want_lo) = (d[0].max(d[1]).max(d[2]), d[0].min(d[1]).min(d[2]));
            // Two equal values are found from the cubic's double root, in
            // general only to the square root of the rounding of J3 (these
            // four came out within 1.5e-16 of the scale).
            let double = d.windows(2).any(|w| w[0] == w[1]);
            let tol = if double { 1e-7 } else { 1e-13 };
            assert!((hi - want_hi).abs() <= tol * scale, "{d:?}: max {hi}");
            assert!((lo - want_lo).abs() <= tol * scale, "{d:?}: min {lo}");
        }
        assert_eq!(deviator_extremes(&[0.0; 6]), (0.0, 0.0));
    }

    /// Four lanes with histories of their own (random strain increments
    /// from elastic to crushing, some lanes resting while others load) give
    /// each lane exactly what the same history gives a point alone: no lane
    /// takes another's path (the all-undamaged shortcut, the returns, the
    /// damage), bit for bit.
    #[test]
    fn lanes_are_independent_points() {
        let mat = tp91();
        let mut rng = crate::random::Rng::seed_from_u64(91);
        let mut states = [CdpState::default(); LANES];
        let mut stress = [F4::ZERO; 6];
        let mut points = [Point::default(); LANES];
        let (mut returns, mut shortcuts) = (0, 0);
        let mut heading = [[0.0; 6]; LANES];
        for step in 0..4000 {
            if step % 50 == 0 {
                heading =
                    std::array::from_fn(|_| std::array::from_fn(|_| 2.0 * rng.uniform() - 1.0));
            }
            let incs: [[f64; 6]; LANES] = std::array::from_fn(|l| {
                // Lane l rests in one step of (l + 2); the rest load along a
                // heading that changes every 50 steps, with some scatter.
                if step % (l + 2) == 0 {
                    return [0.0; 6];
                }
                std::array::from_fn(|i| 1e-5 * (heading[l][i] + rng.uniform() - 0.5))
            });
            let deps: Sym6 = std::array::from_fn(|i| F4(std::array::from_fn(|l| incs[l][i])));
            let before = states;
            mat.update(&mut states, &deps, F4::splat(0.025), &mut stress);
            if states
                .iter()
                .all(|s| s.damage_t == 0.0 && s.damage_c == 0.0)
            {
                shortcuts += 1;
            }
            for (l, p) in points.iter_mut().enumerate() {
                p.step(&mat, &incs[l]);
                if states[l].kappa_t != before[l].kappa_t || states[l].kappa_c != before[l].kappa_c
                {
                    returns += 1;
                }
                assert_eq!(states[l], p.state, "lane {l}, step {step}");
                for i in 0..6 {
                    assert_eq!(stress[i].0[l], p.stress[i], "lane {l}, step {step}");
                }
            }
        }
        // The histories reach every path: the shortcut, returns, cracking
        // and crushing.
        assert!(
            shortcuts > 0 && returns > 1000,
            "{shortcuts} shortcuts, {returns} returns"
        );
        assert!(states.iter().all(|s| s.damage_t > 0.25));
        assert!(states.iter().any(|s| s.damage_c == MAX_DAMAGE));
        let mut out = Vec::new();
        mat.fields(&states[0], &mut out);
        assert_eq!(out.len(), mat.field_names().len());
    }
}
