//! Parameter metadata and validation errors shared by the base model and its
//! effects: every parameter is described once, next to the equation it
//! belongs to, and host tools (fitting, export, documentation) read these
//! descriptions instead of keeping their own lists.

use core::fmt;

/// How a parameter's value changes with the units of the data, so that host
/// tools can fit in normalised units and convert back.
///
/// `D` is the displacement unit, `F` the force unit, `E = F*D` the energy unit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Unit {
    /// A pure number.
    Dimensionless,
    /// F/D (initial stiffness).
    Stiffness,
    /// D (a hysteretic displacement such as the pinching width psi).
    Displacement,
    /// D^-n (beta and gamma: `beta |z|^n` is dimensionless).
    DisplacementPowMinusN,
    /// 1/E (degradation rates).
    PerEnergy,
    /// D/E (growth of the pinching width with energy).
    DisplacementPerEnergy,
    /// E (an energy, such as the validity limit).
    Energy,
}

/// Description of one model parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParamSpec {
    /// Name used in parameter files, on the command line and in tables
    /// (`"delta_nu"`).
    pub name: &'static str,
    /// The thesis' symbol.
    pub symbol: &'static str,
    /// The thesis equation the parameter appears in.
    pub equation: &'static str,
    /// The value that switches its effect off (for base parameters: a
    /// typical value).
    pub off: f32,
    /// How the value scales with the units of the data.
    pub unit: Unit,
    /// A default search range for fitting, in units normalised by the data's
    /// reference displacement, force and energy (see the host tools).
    pub fit_range: (f32, f32),
    /// One line of documentation.
    pub doc: &'static str,
}

/// The rule a rejected parameter broke.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum Rule {
    /// The value is NaN or infinite.
    NotFinite,
    /// The value must be greater than zero.
    NotPositive,
    /// The value must be zero or greater.
    Negative,
    /// The value must not be zero (the pinching width's factors, whose
    /// sign does not matter: eq. 3.11 enters h(z) squared).
    Zero,
    /// The value must lie in [0, 1].
    NotAFraction,
    /// The value must lie in (-1, 1) (the asymmetries).
    NotASignedFraction,
    /// The ultimate hysteretic displacement Zu = (A/(nu(beta+gamma)))^(1/n)
    /// (eq. 3.12) is undefined because beta + gamma <= 0; pinching needs it.
    ZuUndefined,
    /// This degradation rate drives its function (A, nu, eta or the pinching
    /// width) to zero inside `[0, energy_limit]`; lower `energy_limit` or the
    /// rate.
    DegradesToZero,
    /// The pinching function h(z) (eq. 3.9) would become negative (zeta1 > 1)
    /// inside `[0, energy_limit]`, which reverses the hysteretic rate.
    PinchingReversesRate,
    /// A factor derived from this parameter and the others (for asymmetry the
    /// strength factors `(1 ± a)^-n`; for plain Bouc-Wen `Zu^n = 1/(beta +
    /// gamma)`, the value of `|z|^n` at the asymptote, and the stiffness
    /// `k0 (1 + |beta - gamma| Zu^n)` of a reversal there; with degradation
    /// and asymmetry the asymptote `A / (nu nu_a (beta + gamma))`) is too
    /// large for the arithmetic.
    DerivedOverflow,
    /// beta < 0 with an effect that reads the energy: unloading is then softer than loading
    /// (eq. 3.4 with `sgn(du z) = -1` gives `A - |z|^n (gamma - beta)`), and the energy
    /// `∫ z du` falls below zero, outside the range `[0, energy_limit]` on which degradation and
    /// pinching were validated. Plain Bouc-Wen allows it.
    EnergyCanFallBelowZero,
    /// A required parameter is missing.
    Missing,
    /// The name is not a parameter of the model.
    Unknown,
}

impl Rule {
    /// Whether the rule is checked over `[0, energy_limit]`, so that a value
    /// it refuses may hold under a lower limit (a degradation rate that
    /// reaches zero, or pinching that reverses the rate, only at some energy).
    pub const fn bounded_by_energy_limit(self) -> bool {
        matches!(self, Rule::DegradesToZero | Rule::PinchingReversesRate)
    }

    fn text(self) -> &'static str {
        match self {
            Rule::NotFinite => "must be a finite number",
            Rule::NotPositive => "must be greater than zero",
            Rule::Negative => "must not be negative",
            Rule::Zero => "must not be zero",
            Rule::NotAFraction => "must lie in [0, 1]",
            Rule::NotASignedFraction => "must lie in (-1, 1)",
            Rule::ZuUndefined => {
                "pinching needs Zu = (A/(nu(beta+gamma)))^(1/n) (eq. 3.12), undefined when beta + gamma <= 0"
            }
            Rule::DegradesToZero => {
                "drives its degradation function to zero within [0, energy_limit]; lower energy_limit or the rate"
            }
            Rule::PinchingReversesRate => {
                "makes zeta1 exceed 1 within [0, energy_limit], so h(z) (eq. 3.9) turns negative"
            }
            Rule::DerivedOverflow => {
                "makes a factor derived from it (for asymmetry (1 ± a)^-n, for plain Bouc-Wen Zu^n = 1/(beta + gamma) or the stiffness of a reversal at Zu, with degradation and asymmetry Zu^n = A/(nu nu_a (beta + gamma))) too large for the arithmetic"
            }
            Rule::EnergyCanFallBelowZero => {
                "is negative, which makes unloading softer than loading, so the energy read by degradation and pinching can fall below zero"
            }
            Rule::Missing => "is required but missing",
            Rule::Unknown => "is not a parameter of this model",
        }
    }
}

/// A parameter set was rejected: `field` broke `rule`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ParamError {
    /// The parameter's name as in [`ParamSpec::name`].
    pub field: &'static str,
    /// The rule it broke.
    pub rule: Rule,
}

impl ParamError {
    pub(crate) const fn new(field: &'static str, rule: Rule) -> Self {
        ParamError { field, rule }
    }
}

impl fmt::Display for ParamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} {}", self.field, self.rule.text())
    }
}

impl core::error::Error for ParamError {}
