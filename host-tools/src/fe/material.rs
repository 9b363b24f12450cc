//! Material interfaces of the solver and the elastic materials of part 1.
//!
//! The solver is generic over one [`SolidMaterial`] for the concrete
//! hexahedra and one [`BarMaterial`] type for the embedded trusses (one
//! instance per bar set, so longitudinal bars and spirals can differ). A
//! material advances stress by a strain increment and keeps whatever history
//! it needs in its `State`, one per element (or per truss). The solver owns
//! the kinematics (strain increments, the Jaumann rotation of stress, bulk
//! viscosity, hourglass control) and the energy bookkeeping, so a material
//! only does constitutive work. Concrete damaged plasticity and hardening
//! steel (thesis 2.2, issue 8) implement these two traits.

use super::simd::{F4, LANES};

/// Isotropic linear elasticity with a density: the initial properties every
/// solid material reports, used for the stable time step, the hourglass
/// stiffness and the bulk viscosity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Isotropic {
    /// Young's modulus, Pa.
    pub e: f64,
    /// Poisson's ratio.
    pub nu: f64,
    /// Mass density, kg/m^3.
    pub density: f64,
}

impl Isotropic {
    /// Lame's constants `(lambda, mu)`, Pa.
    pub fn lame(&self) -> (f64, f64) {
        let mu = self.e / (2.0 * (1.0 + self.nu));
        let lambda = self.e * self.nu / ((1.0 + self.nu) * (1.0 - 2.0 * self.nu));
        (lambda, mu)
    }

    /// Shear modulus, Pa.
    pub fn shear_modulus(&self) -> f64 {
        self.lame().1
    }

    /// Dilatational wave speed `sqrt((lambda + 2 mu) / rho)`, m/s.
    pub fn wave_speed(&self) -> f64 {
        let (l, m) = self.lame();
        ((l + 2.0 * m) / self.density).sqrt()
    }
}

/// Stress and strain components in the order `xx, yy, zz, xy, yz, zx`;
/// shear strain components are tensor components (half the engineering
/// shear strain).
pub type Sym6 = [F4; 6];

/// A constitutive law for the hexahedra, evaluated for a batch of
/// [`LANES`] elements at once.
pub trait SolidMaterial: Sync {
    /// History of one element (plastic strain, damage, ...).
    type State: Copy + Default + Send + Sync;

    /// Initial elastic properties and density.
    fn initial(&self) -> Isotropic;

    /// Advances `stress` (already rotated to the end of the step) by the
    /// strain increment `deps`. `char_length` is each element's
    /// characteristic length (m), for regularised softening laws.
    fn update(
        &self,
        state: &mut [Self::State; LANES],
        deps: &Sym6,
        char_length: F4,
        stress: &mut Sym6,
    );

    /// Fraction of its initial stiffness each element keeps: `1 - d` for a
    /// material with scalar damage, 1 (the default) for one without. The
    /// hourglass stiffness follows it (see [`super::hex8::step`]).
    #[inline(always)]
    fn retained_stiffness(&self, _state: &[Self::State; LANES]) -> F4 {
        F4::splat(1.0)
    }

    /// Names of the scalar history fields written to VTK files.
    fn field_names(&self) -> &'static [&'static str] {
        &[]
    }

    /// The history fields of one element, in the order of
    /// [`SolidMaterial::field_names`].
    fn fields(&self, _state: &Self::State, _out: &mut Vec<f64>) {}
}

/// A uniaxial constitutive law for the embedded bars.
pub trait BarMaterial: Sync {
    /// History of one truss element.
    type State: Copy + Default + Send + Sync;

    /// Young's modulus, Pa.
    fn modulus(&self) -> f64;

    /// Mass density, kg/m^3.
    fn density(&self) -> f64;

    /// Advances the axial `stress` by the strain increment `deps`.
    fn update(&self, state: &mut Self::State, deps: f64, stress: &mut f64);
}

/// Linear isotropic elasticity (Hooke's law in rate form,
/// `dsigma = lambda tr(deps) I + 2 mu deps`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Elastic {
    props: Isotropic,
    lambda: f64,
    two_mu: f64,
}

impl Elastic {
    /// An elastic material with the given properties.
    pub fn new(props: Isotropic) -> Self {
        let (lambda, mu) = props.lame();
        Elastic {
            props,
            lambda,
            two_mu: 2.0 * mu,
        }
    }
}

impl SolidMaterial for Elastic {
    type State = ();

    fn initial(&self) -> Isotropic {
        self.props
    }

    #[inline(always)]
    fn update(&self, _state: &mut [(); LANES], deps: &Sym6, _h: F4, stress: &mut Sym6) {
        let lt = (deps[0] + deps[1] + deps[2]) * self.lambda;
        for i in 0..3 {
            stress[i] += deps[i].mul_add(F4::splat(self.two_mu), lt);
        }
        for i in 3..6 {
            stress[i] += deps[i] * self.two_mu;
        }
    }
}

/// A linear elastic bar.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ElasticBar {
    /// Young's modulus, Pa.
    pub e: f64,
    /// Mass density, kg/m^3.
    pub density: f64,
}

impl BarMaterial for ElasticBar {
    type State = ();

    fn modulus(&self) -> f64 {
        self.e
    }

    fn density(&self) -> f64 {
        self.density
    }

    fn update(&self, _state: &mut (), deps: f64, stress: &mut f64) {
        *stress += self.e * deps;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lame_constants_and_wave_speed() {
        let m = Isotropic {
            e: 25e9,
            nu: 0.2,
            density: 2400.0,
        };
        let (l, mu) = m.lame();
        assert!((mu - 25e9 / 2.4).abs() < 1.0);
        assert!((l - 25e9 * 0.2 / (1.2 * 0.6)).abs() < 1.0);
        // c_d = sqrt(E (1 - nu) / ((1 + nu)(1 - 2 nu) rho))
        let c = (25e9f64 * 0.8 / (1.2 * 0.6 * 2400.0)).sqrt();
        assert!((m.wave_speed() - c).abs() < 1e-9 * c);
    }

    #[test]
    fn uniaxial_strain_gives_constrained_modulus() {
        let p = Isotropic {
            e: 30e9,
            nu: 0.25,
            density: 2400.0,
        };
        let mat = Elastic::new(p);
        let mut s = [F4::ZERO; 6];
        let mut d = [F4::ZERO; 6];
        d[0] = F4::splat(1e-4);
        d[3] = F4::splat(2e-4);
        mat.update(&mut [(); LANES], &d, F4::splat(0.025), &mut s);
        let (l, mu) = p.lame();
        assert!((s[0].0[2] - (l + 2.0 * mu) * 1e-4).abs() < 1e-3);
        assert!((s[1].0[1] - l * 1e-4).abs() < 1e-3);
        assert!((s[3].0[3] - 2.0 * mu * 2e-4).abs() < 1e-3);
        assert_eq!(s[4], F4::ZERO);
    }
}
