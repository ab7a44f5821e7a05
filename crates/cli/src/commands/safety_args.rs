//! The arguments `flexrig safety` and `flexrig safety-map` share: the contact kind, the contact
//! law and area model for pressure, and the joint of the simulated impact.

use clap::{Args, ValueEnum};
use flexrig::Error;
use flexrig::safety::map::MapJoint;
use flexrig::safety::{ContactAreaModel, ContactLaw};

use super::impact_args::JointArg;

/// Contact kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ContactArg {
    /// A free body region struck (Table A.3's m_H, transient limits).
    Transient,
    /// A clamped body region (m_H = ∞, quasi-static limits).
    QuasiStatic,
}

/// Contact-area model for pressure.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum AreaModelArg {
    /// A = π R δ (elastic half-space; needs --radius).
    HertzSphere,
    /// A = π(2Rδ − δ²) (thin layer on a rigid backing; needs --radius).
    ThinLayer,
    /// A fixed area (needs --contact-area).
    Fixed,
}

/// The contact flags of `flexrig safety` and `flexrig safety-map`: the Hertz law (or a bundled
/// material, or the body region's spring) and the contact-area model for pressure.
#[derive(Debug, Args)]
pub struct ContactLawArgs {
    /// Contact stiffness k_c [N/mⁿ] (with --n; default: the region's body spring, n = 1).
    #[arg(
        long = "k-c",
        value_name = "K",
        requires = "n",
        conflicts_with = "material"
    )]
    pub k_c: Option<f64>,
    /// Hertz exponent n (with --k-c).
    #[arg(long, value_name = "N", requires = "k_c")]
    pub n: Option<f64>,
    /// A bundled material for the Hertz law (abs, skinned_aluminium, skinned_iron); its dome
    /// gives the default Hertz-sphere area.
    #[arg(long, value_name = "NAME")]
    pub material: Option<String>,
    /// Contact-area model for pressure (default: hertz-sphere with --radius, fixed with
    /// --contact-area, else the design's dome: a scene's, or the material's with --material;
    /// without any, pressure is not assessed). A dome's models need a contact law with n > 1.
    #[arg(long = "area-model", value_enum)]
    pub area_model: Option<AreaModelArg>,
    /// Dome radius R [m] of the hertz-sphere and thin-layer area models (alone: hertz-sphere).
    #[arg(long, value_name = "M")]
    pub radius: Option<f64>,
    /// Contact area of the fixed area model (alone: fixed), with its unit: 1cm2 (the unit of
    /// the standard's pressures), 1e-4m2 or 100mm2; a bare number is refused.
    #[arg(long = "contact-area", value_name = "AREA")]
    pub contact_area: Option<String>,
}

impl ContactLawArgs {
    /// The contact law: `--k-c` with `--n`, else `--material`, else the region's body spring.
    pub fn law(&self) -> ContactLaw {
        match (self.k_c, self.n, &self.material) {
            (Some(k_c), Some(n), _) => ContactLaw::Hertz { k_c, n },
            (_, _, Some(m)) => ContactLaw::Material(m.clone()),
            _ => ContactLaw::BodySpring,
        }
    }

    /// The contact-area model of `--area-model` with the dimension it needs; without
    /// `--area-model`, the Hertz sphere of `--radius` or the fixed `--contact-area`.
    pub fn area_model(&self) -> Result<Option<ContactAreaModel>, Error> {
        let area = self
            .contact_area
            .as_deref()
            .map(|a| flexrig::safety::measured::parse_area("--contact-area", a))
            .transpose()?;
        let unused = |flag: &str, model: &str| Error::InvalidArgument {
            arg: flag.into(),
            value: "(given)".into(),
            allowed: format!("--area-model {model} does not use it: leave it out"),
        };
        Ok(match self.area_model {
            None => match (self.radius, area) {
                (Some(_), Some(_)) => {
                    return Err(missing(
                        "--area-model",
                        "--radius and --contact-area together need --area-model to say which \
                         model (hertz-sphere, thin-layer or fixed)",
                    ));
                }
                (Some(radius_m), None) => Some(ContactAreaModel::HertzSphere { radius_m }),
                (None, Some(area_m2)) => Some(ContactAreaModel::Fixed { area_m2 }),
                (None, None) => None,
            },
            Some(AreaModelArg::HertzSphere | AreaModelArg::ThinLayer) if area.is_some() => {
                return Err(unused("--contact-area", "hertz-sphere or thin-layer"));
            }
            Some(AreaModelArg::Fixed) if self.radius.is_some() => {
                return Err(unused("--radius", "fixed"));
            }
            Some(AreaModelArg::HertzSphere) => Some(ContactAreaModel::HertzSphere {
                radius_m: self.radius.ok_or_else(|| {
                    missing("--radius", "--area-model hertz-sphere needs --radius")
                })?,
            }),
            Some(AreaModelArg::ThinLayer) => Some(ContactAreaModel::ThinLayer {
                radius_m: self
                    .radius
                    .ok_or_else(|| missing("--radius", "--area-model thin-layer needs --radius"))?,
            }),
            Some(AreaModelArg::Fixed) => Some(ContactAreaModel::Fixed {
                area_m2: area.ok_or_else(|| {
                    missing(
                        "--contact-area",
                        "--area-model fixed needs --contact-area (e.g. 1cm2)",
                    )
                })?,
            }),
        })
    }
}

pub(crate) fn missing(flag: &str, needed: &str) -> Error {
    Error::InvalidArgument {
        arg: flag.into(),
        value: "(missing)".into(),
        allowed: needed.into(),
    }
}

/// The joint of `--joint` with `--rotor-inertia` (only, and always, with free-hub).
pub(crate) fn map_joint(joint: JointArg, rotor_inertia: Option<f64>) -> Result<MapJoint, Error> {
    match (joint, rotor_inertia) {
        (JointArg::Held, None) => Ok(MapJoint::Held),
        (JointArg::Held, Some(j)) => Err(Error::InvalidArgument {
            arg: "--rotor-inertia".into(),
            value: flexrig::shared::output::display_number(j),
            allowed: "only with --joint free-hub".into(),
        }),
        (JointArg::FreeHub, None) => Err(missing(
            "--rotor-inertia",
            "--joint free-hub needs --rotor-inertia (kg·m², > 0)",
        )),
        (JointArg::FreeHub, Some(j)) => Ok(MapJoint::FreeHub { rotor_inertia: j }),
    }
}
