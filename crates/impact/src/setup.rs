//! The free-mass impact set-up (the paper's Fig. 5, issue 14) and its result.

use flexrig_contact::{ContactLaw, DampingSpec, Hertz};
use serde::{Deserialize, Serialize};

use crate::ImpactError;

/// The robot link: the same for the CJ and the CL design (paper §IV).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LinkParams {
    /// Link mass m_r \[kg\] (uniform).
    pub m_r: f64,
    /// Link length L \[m\].
    pub length: f64,
    /// Lateral tip stiffness k_δ = 3EI/L³ \[N/m\] (Eq. 3: the CJ spring k_θr = k_δ L²).
    pub k_delta: f64,
    /// Tip payload m_e \[kg\] (a point mass at the tip; 0 allowed).
    pub m_e: f64,
}

impl LinkParams {
    /// Bending stiffness EI = k_δ L³/3 \[N·m²\].
    pub fn ei(&self) -> f64 {
        self.k_delta * self.length.powi(3) / 3.0
    }

    /// Mass per length ρA = m_r/L \[kg/m\].
    pub fn rho_a(&self) -> f64 {
        self.m_r / self.length
    }

    /// The CJ torsion spring k_θr = 3EI/L = k_δ L² \[N·m/rad\] (Eq. 3).
    pub fn k_theta(&self) -> f64 {
        self.k_delta * self.length * self.length
    }

    /// The rigid link's inertia about the joint over L², m_e + m_r/3 \[kg\]: the CJ's mass at
    /// the tip.
    pub fn cj_tip_mass(&self) -> f64 {
        self.m_e + self.m_r / 3.0
    }

    pub(crate) fn validate(&self) -> Result<(), ImpactError> {
        in_range("m_r", self.m_r, 1e-6, 1e6)?;
        in_range("length", self.length, 1e-3, 1e3)?;
        in_range("k_delta", self.k_delta, 1e-3, 1e12)?;
        if !(self.m_e.is_finite() && (0.0..=1e6).contains(&self.m_e)) {
            return Err(ImpactError::invalid(
                "m_e",
                self.m_e,
                "must lie in [0, 1e6] kg",
            ));
        }
        Ok(())
    }
}

/// The robot's joint during the impact.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case", tag = "joint")]
pub enum Joint {
    /// Driven at constant speed: in the joint's frame the robot is at rest and the head arrives
    /// at v0 (the test bed of §VI, robot standing still, struck by the operator).
    Held,
    /// A free hub: the motor's rotor inertia behind the torsion spring (CJ) or under the clamped
    /// beam (CL); the robot turns at v0/L (tip speed v0) into a head at rest.
    FreeHub {
        /// Rotor inertia J_R about the joint axis [kg·m²], > 0.
        rotor_inertia: f64,
    },
}

/// Mesh and step of the CL's finite-element solution.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ClSolver {
    /// Hermite-cubic elements along the link.
    pub elements: usize,
    /// Time steps over the shortest contact the set-up can have (the head against the payload
    /// alone).
    pub steps_per_contact: usize,
    /// `Some(k)`: the beam reduced to its lowest k modes plus the static correction shape of the
    /// tip's transverse DOF (flexrig-beam's `ReducedModel`); `None`: the full FE model.
    pub modes: Option<usize>,
}

impl ClSolver {
    /// The default: 256 elements, 800 steps per contact. The soft-link cases need the mesh: the
    /// payload's short impact bends only a tip zone of length ≈ (EI/ρA)^{1/4} √t_c (L/60 for the
    /// Fig. 6 soft link); their peaks moved by 1.7e-3 from 64 to 128 elements and by 8e-5 from
    /// 128 to 256 (`flexrig eta --elements`).
    pub const DEFAULT: ClSolver = ClSolver {
        elements: 256,
        steps_per_contact: 800,
        modes: None,
    };

    /// Checks the mesh and the step count; the error names the field.
    pub fn validate(&self) -> Result<(), ImpactError> {
        if !(2..=4096).contains(&self.elements) {
            return Err(ImpactError::invalid(
                "elements",
                self.elements,
                "must lie in [2, 4096]",
            ));
        }
        if !(20..=1_000_000).contains(&self.steps_per_contact) {
            return Err(ImpactError::invalid(
                "steps_per_contact",
                self.steps_per_contact,
                "must lie in [20, 1000000]",
            ));
        }
        if let Some(k) = self.modes {
            let most = 3 * self.elements.min(flexrig_beam::modal::MAX_MODAL_ELEMENTS);
            if !(1..=most).contains(&k) || self.elements > flexrig_beam::modal::MAX_MODAL_ELEMENTS {
                return Err(ImpactError::invalid(
                    "modes",
                    k,
                    format!(
                        "must lie in [1, 3 × elements] with at most {} elements (a dense \
                         eigenproblem)",
                        flexrig_beam::modal::MAX_MODAL_ELEMENTS
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// A free head striking the tip payload of a link.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FreeMassImpact {
    /// Head (human) mass m_h \[kg\].
    pub m_h: f64,
    /// Approach speed v0 \[m/s\] (head towards the tip, or tip towards the head).
    pub v0: f64,
    /// The link.
    pub link: LinkParams,
    /// The joint during the impact.
    pub joint: Joint,
    /// The elastic contact law f = k_c δ^n (Eq. 4).
    pub contact: Hertz,
    /// Damping added to it ([`DampingSpec::NONE`]: the paper's elastic contact); the
    /// restitution-based models set χ from v0.
    pub damping: DampingSpec,
}

impl Joint {
    /// Checks the joint's parameters (a free hub's rotor inertia in [1e-12, 1e12] kg·m²).
    pub fn validate(&self) -> Result<(), ImpactError> {
        if let Joint::FreeHub { rotor_inertia } = *self {
            in_range("rotor_inertia", rotor_inertia, 1e-12, 1e12)?;
        }
        Ok(())
    }
}

impl FreeMassImpact {
    /// Checks every parameter; the error names it and the allowed range.
    pub fn validate(&self) -> Result<(), ImpactError> {
        in_range("m_h", self.m_h, 1e-6, 1e9)?;
        in_range("v0", self.v0, 1e-6, 1e3)?;
        self.link.validate()?;
        self.joint.validate()?;
        self.law()?;
        self.damping
            .check_overdamping(self.contact, self.payload_reduced_mass(), self.v0)?;
        Ok(())
    }

    /// The contact law: [`Self::contact`] with [`Self::damping`] at the approach speed v0.
    pub fn law(&self) -> Result<Box<dyn ContactLaw>, ImpactError> {
        Ok(self.damping.law(self.contact, self.v0)?)
    }

    /// Duration \[s\] of an undamped Hertz impact of the head against the payload alone (the
    /// shortest contact the link can offer): t = 2 (δ_max/v0) ∫₀¹ ds/√(1 − s^{n+1}) with
    /// ½ μ v0² = k δ_max^{n+1}/(n+1), μ the reduced mass of m_h and m_e (m_e + m_r/100 when the
    /// payload is 0).
    pub fn payload_contact_time(&self) -> f64 {
        self.payload_contact_time_with(hertz_time_integral(self.contact.n()))
    }

    /// [`Self::payload_contact_time`] from the law's time integral ∫₀¹ ds/√(1 − s^{n+1})
    /// ([`hertz_time_integral`] of its n), which a caller running many speeds of one design
    /// computes once: the same number.
    pub fn payload_contact_time_with(&self, time_integral: f64) -> f64 {
        let mu = self.payload_reduced_mass();
        let (k, n) = (self.contact.k(), self.contact.n());
        let delta_max = ((n + 1.0) * mu * self.v0 * self.v0 / (2.0 * k)).powf(1.0 / (n + 1.0));
        2.0 * delta_max / self.v0 * time_integral
    }
}

impl FreeMassImpact {
    /// Reduced mass μ \[kg\] of the head and the payload alone (m_e, or m_r/100 when the
    /// payload is 0): the pair of the shortest contact the link can offer.
    pub fn payload_reduced_mass(&self) -> f64 {
        let m_tip = if self.link.m_e > 0.0 {
            self.link.m_e
        } else {
            self.link.m_r / 100.0
        };
        self.m_h * m_tip / (self.m_h + m_tip)
    }
}

/// ∫₀¹ ds/√(1 − s^{n+1}), by s = 1 − u² (a smooth integrand 2u/√(1 − (1 − u²)^{n+1})) and
/// composite Simpson on 400 panels (error < 1e-9; π/2 for n = 1).
pub fn hertz_time_integral(n: f64) -> f64 {
    let g = |u: f64| {
        if u == 0.0 {
            2.0 / (n + 1.0).sqrt()
        } else {
            2.0 * u / (1.0 - (1.0 - u * u).powf(n + 1.0)).sqrt()
        }
    };
    let panels = 400;
    let h = 1.0 / panels as f64;
    let mut sum = g(0.0) + g(1.0);
    for i in 1..panels {
        sum += g(i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    sum * h / 3.0
}

fn in_range(field: &str, value: f64, lo: f64, hi: f64) -> Result<(), ImpactError> {
    if value.is_finite() && (lo..=hi).contains(&value) {
        Ok(())
    } else {
        Err(ImpactError::invalid(
            field,
            value,
            flexrig_contact::validate::interval_with_hint(field, value, lo, hi),
        ))
    }
}

/// One contact of a run.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ContactEvent {
    /// Onset time \[s\] (serialised as `onset_time_s`, the test-bed run's name).
    #[serde(rename = "onset_time_s")]
    pub onset_s: f64,
    /// Peak force \[N\].
    pub peak_force_n: f64,
    /// Time of the peak \[s\].
    pub time_of_peak_s: f64,
    /// Contact duration \[s\].
    pub duration_s: f64,
}

/// How a run ended.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case", tag = "ended", content = "at_s")]
pub enum RunEnd {
    /// At the separation of the first contact (the first-contact solvers).
    FirstSeparation,
    /// The bodies parted for good: moving apart with a gap larger than the link's tip can ever
    /// close with its vibration energy (a bound, not a guess); the time \[s\].
    PartedForGood(f64),
    /// At the end of the stated window \[s\], the bodies still able to meet again.
    Window(f64),
    /// The step budget ran out at this time \[s\] (the contacts so far are exact to the
    /// tolerance; later ones are not known).
    StepBudget(f64),
    /// The test bed's operator, out of contact and moving away, turned back at the apex of
    /// its rebound at this time \[s\]: every contact of the swing is in (a later one would
    /// be the pendulum's return swing under gravity, a new strike).
    Rebound(f64),
}

/// The result of a free-mass impact from the onset of the first contact (t = 0).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ImpactOutcome {
    /// The first contact.
    pub first: ContactEvent,
    /// Every contact in the window, in order (the first-contact solvers: the first alone).
    pub contacts: Vec<ContactEvent>,
    /// The contact with the largest peak in the window.
    pub overall: ContactEvent,
    /// How the run ended.
    pub ended: RunEnd,
    /// Relative approach speed at the last separation (negative: the bodies part) \[m/s\];
    /// serialised as the parting speed `separation_velocity_mps` (positive: the bodies part),
    /// the test-bed run's name.
    #[serde(
        rename = "separation_velocity_mps",
        serialize_with = "crate::setup::negated"
    )]
    pub separation_rate_mps: f64,
    /// Mechanical energy at onset and at the end \[J\] (undamped contact: equal up to the
    /// integration error).
    pub energy_j: (f64, f64),
    /// Time steps taken (CL) or right-hand-side evaluations (CJ) (serialised as `steps`).
    #[serde(rename = "steps")]
    pub work: usize,
}

/// Serialises −x (a closing rate as a parting speed).
pub(crate) fn negated<S: serde::Serializer>(x: &f64, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_f64(-x)
}

impl ImpactOutcome {
    /// The outcome of a run that stopped at the first separation.
    pub(crate) fn first_only(
        first: ContactEvent,
        separation_rate_mps: f64,
        energy_j: (f64, f64),
        work: usize,
    ) -> ImpactOutcome {
        ImpactOutcome {
            first,
            contacts: vec![first],
            overall: first,
            ended: RunEnd::FirstSeparation,
            separation_rate_mps,
            energy_j,
            work,
        }
    }
}
