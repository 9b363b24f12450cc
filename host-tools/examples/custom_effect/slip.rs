//! A user-defined effect: slip, as in reinforcing bars slipping in their
//! anchorage. Right after a load reversal the member moves over a band of
//! displacement at low stiffness before it picks up load again: a flat
//! stretch of force near zero hysteretic displacement, of constant width and
//! depth (unlike pinching, whose band grows with the dissipated energy).
//!
//! ```text
//! h_slip(z) = 1 - slip_depth exp(-(z / slip_width)^2)
//! ```
//!
//! multiplies the z-rate like the pinching factor of eq. 3.9. Off:
//! `slip_depth = 0`.

use hyst::model::CustomEffect;
use hysteresis::bwbn::effects::{At, Coefficients, Effect};
use hysteresis::bwbn::{BoucWen, ParamError, ParamSpec, Rule, Unit};

/// The effect's parameters.
pub struct Slip {
    depth: f64,
    width: f64,
}

impl Effect<f64> for Slip {
    fn apply(&self, _: &BoucWen<f64>, _: Option<f64>, at: &At<f64>, c: &mut Coefficients<f64>) {
        let x = at.z / self.width;
        c.h *= 1.0 - self.depth * (-x * x).exp();
    }
}

/// Registers as `slip`.
pub struct SlipEffect;

/// The parameters: depth (fraction of the stiffness lost) and width (in
/// the record's displacement unit).
pub const PARAMS: [ParamSpec; 2] = [
    ParamSpec {
        name: "slip_depth",
        symbol: "s",
        equation: "h_slip = 1 - s exp(-(z/w)^2)",
        off: 0.0,
        unit: Unit::Dimensionless,
        fit_range: (0.0, 0.95),
        doc: "fraction of the hysteretic stiffness lost in the slip band",
    },
    ParamSpec {
        name: "slip_width",
        symbol: "w",
        equation: "h_slip = 1 - s exp(-(z/w)^2)",
        off: 0.2,
        unit: Unit::Displacement,
        fit_range: (0.02, 1.0),
        doc: "half-width of the slip band in z",
    },
];

impl CustomEffect for SlipEffect {
    fn name(&self) -> &'static str {
        "slip"
    }
    fn params(&self) -> &'static [ParamSpec] {
        &PARAMS
    }
    fn doc(&self) -> &'static str {
        "bars slip after each reversal: a band of low stiffness of constant width around z = 0"
    }
    fn build(
        &self,
        _: &BoucWen<f64>,
        v: &[f64],
    ) -> Result<Box<dyn Effect<f64> + Send + Sync>, ParamError> {
        let (depth, width) = (v[0], v[1]);
        if !(0.0..1.0).contains(&depth) {
            return Err(ParamError {
                field: "slip_depth",
                rule: Rule::NotAFraction,
            });
        }
        if width.is_nan() || width <= 0.0 {
            return Err(ParamError {
                field: "slip_width",
                rule: Rule::NotPositive,
            });
        }
        Ok(Box::new(Slip { depth, width }))
    }
}
