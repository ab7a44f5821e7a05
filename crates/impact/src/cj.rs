//! The compliant joint under a free head: the rigid link is one degree of freedom (tip
//! deflection w = Lφ, tip inertia J/L² = m_e + m_r/3 on the spring k_θr/L² = k_δ), the head one
//! more, and a free hub adds the rotor (r = Lψ, inertia J_R/L²) behind the spring:
//!
//! m_h ẍ_h = −f,  M ẅ = −k_δ (w − r) + f,  M_R r̈ = k_δ (w − r),  f = f(δ, δ̇), δ = x_h − w,
//!
//! with M = m_e + m_r/3, M_R = J_R/L² (held joint: r ≡ 0) and f any law of flexrig-contact
//! (k_c ⟨δ⟩ⁿ, Eq. 4, when undamped). Integrated by DOP853 (flexrig-lumped) from the onset to the
//! separation, which is located on the dense output; so is every local maximum of the force
//! (where ḟ = ∂f/∂δ δ̇ + ∂f/∂δ̇ δ̈ turns negative: for the elastic law, where δ̇ does).

use flexrig_contact::ContactLaw;
use flexrig_lumped::ode::dop853::{Dop853, Dop853Options, OdeSystem, find_root};

use crate::ImpactError;
use crate::setup::{ContactEvent, FreeMassImpact, ImpactOutcome, Joint};
use crate::severity::{CJ_TRACE_SAMPLES, ContactTrace};

/// State: head position and speed, tip deflection and rate, rotor (tip units) and rate.
type Y = [f64; 6];

struct CjSystem<'a> {
    m_h: f64,
    m_tip: f64,
    /// 1/M_R (0 for the held joint).
    inv_m_rotor: f64,
    k_delta: f64,
    law: &'a dyn ContactLaw,
}

impl CjSystem<'_> {
    fn force(&self, y: &Y) -> f64 {
        self.law.force(y[0] - y[2], y[1] - y[3])
    }

    /// ḟ [N/s] along the motion: ∂f/∂δ δ̇ + ∂f/∂δ̇ δ̈.
    fn force_rate(&self, y: &Y) -> f64 {
        let (delta, rate) = (y[0] - y[2], y[1] - y[3]);
        let dy = self.rhs(0.0, y);
        self.law.stiffness(delta, rate) * rate + self.law.damping(delta, rate) * (dy[1] - dy[3])
    }

    fn energy(&self, y: &Y) -> f64 {
        let delta = (y[0] - y[2]).max(0.0);
        let spring = y[2] - y[4];
        let rotor = if self.inv_m_rotor > 0.0 {
            0.5 * y[5] * y[5] / self.inv_m_rotor
        } else {
            0.0
        };
        0.5 * self.m_h * y[1] * y[1]
            + 0.5 * self.m_tip * y[3] * y[3]
            + rotor
            + 0.5 * self.k_delta * spring * spring
            + self.law.elastic_energy(delta)
    }
}

impl OdeSystem<6> for CjSystem<'_> {
    fn rhs(&self, _t: f64, y: &Y) -> Y {
        let f = self.force(y);
        let spring = self.k_delta * (y[2] - y[4]);
        [
            y[1],
            -f / self.m_h,
            y[3],
            (f - spring) / self.m_tip,
            y[5],
            spring * self.inv_m_rotor,
        ]
    }
}

/// A one-degree-of-freedom link seen from its tip: mass `m_tip` \[kg\] on the spring `k` \[N/m\]
/// to the joint (or, with a free hub, to a rotor of tip-equivalent mass J_R/L²).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TipOscillator {
    /// Mass at the tip \[kg\].
    pub m_tip: f64,
    /// Stiffness at the tip \[N/m\].
    pub k: f64,
}

/// Runs the CJ impact from the onset to the separation, with relative tolerance `rtol` of the
/// DOP853 integration (the peak's error is of the order of `rtol`).
pub fn run_cj(setup: &FreeMassImpact, rtol: f64) -> Result<ImpactOutcome, ImpactError> {
    let tip = TipOscillator {
        m_tip: setup.link.cj_tip_mass(),
        k: setup.link.k_delta,
    };
    run_tip_oscillator(setup, tip, rtol)
}

/// [`run_cj`] with its contact's traces: the dense output sampled every T/[`CJ_TRACE_SAMPLES`]
/// (T the contact duration of a first run), onset and separation included.
pub fn run_cj_traced(
    setup: &FreeMassImpact,
    rtol: f64,
) -> Result<(ImpactOutcome, ContactTrace), ImpactError> {
    let tip = TipOscillator {
        m_tip: setup.link.cj_tip_mass(),
        k: setup.link.k_delta,
    };
    let first = run_tip_oscillator(setup, tip, rtol)?;
    let dt = first.first.duration_s / CJ_TRACE_SAMPLES as f64;
    let mut trace = ContactTrace::default();
    let outcome = run_tip_oscillator_inner(setup, tip, rtol, Some((dt, &mut trace)))?;
    Ok((outcome, trace))
}

/// Runs the impact of the head on a [`TipOscillator`] (the CJ, or a one-mode model of the CL)
/// with the joint of `setup`, from the onset to the separation.
pub fn run_tip_oscillator(
    setup: &FreeMassImpact,
    tip: TipOscillator,
    rtol: f64,
) -> Result<ImpactOutcome, ImpactError> {
    run_tip_oscillator_inner(setup, tip, rtol, None)
}

/// [`run_tip_oscillator`], with `record` = (Δt \[s\], trace): the dense output sampled every Δt.
fn run_tip_oscillator_inner(
    setup: &FreeMassImpact,
    tip: TipOscillator,
    rtol: f64,
    mut record: Option<(f64, &mut ContactTrace)>,
) -> Result<ImpactOutcome, ImpactError> {
    setup.validate()?;
    if !(rtol.is_finite() && (1e-14..=1e-3).contains(&rtol)) {
        return Err(ImpactError::invalid(
            "rtol",
            rtol,
            "must lie in [1e-14, 1e-3]",
        ));
    }
    if !(tip.m_tip.is_finite() && tip.m_tip > 0.0 && tip.k.is_finite() && tip.k > 0.0) {
        return Err(ImpactError::invalid(
            "tip oscillator",
            format!("m {} kg, k {} N/m", tip.m_tip, tip.k),
            "a mass and a stiffness > 0",
        ));
    }
    let link = setup.link;
    let law = setup.law()?;
    let (inv_m_rotor, y0) = match setup.joint {
        Joint::Held => (0.0, [0.0, setup.v0, 0.0, 0.0, 0.0, 0.0]),
        Joint::FreeHub { rotor_inertia } => (
            link.length * link.length / rotor_inertia,
            [0.0, 0.0, 0.0, -setup.v0, 0.0, -setup.v0],
        ),
    };
    let system = CjSystem {
        m_h: setup.m_h,
        m_tip: tip.m_tip,
        inv_m_rotor,
        k_delta: tip.k,
        law: &*law,
    };
    let t_scale = setup.payload_contact_time();
    let x_scale = setup.v0 * t_scale;
    let options = Dop853Options {
        rtol,
        atol: [
            rtol * x_scale,
            rtol * setup.v0,
            rtol * x_scale,
            rtol * setup.v0,
            rtol * x_scale,
            rtol * setup.v0,
        ],
        first_step: Some(t_scale * 1e-3),
        max_step: t_scale * 0.5,
        max_steps: 10_000_000,
    };
    let mut ode = Dop853::new(&system, 0.0, y0, options);
    let rate = |y: &Y| y[1] - y[3];
    let force_rate = |y: &Y| system.force_rate(y);
    let gap = |y: &Y| y[0] - y[2];
    let mut peak = (0.0_f64, 0.0_f64);
    // the index of the next sample of the recorded trace (at k Δt)
    let mut next_sample = 1usize;
    if let Some((_, trace)) = record.as_mut() {
        trace.push(0.0, 0.0, 0.0);
    }
    // the contact ends when the indentation returns to 0 with the bodies parting
    loop {
        ode.step(&system).map_err(|e| ImpactError::NotFinished {
            design: "CJ",
            reason: e.to_string(),
        })?;
        let (t0, t1) = (ode.t_old(), ode.t());
        let (y_old, y_new) = (*ode.y_old(), *ode.y());
        if let Some((dt, trace)) = record.as_mut()
            && next_sample as f64 * *dt <= t1
        {
            let dense = ode.dense_output(&system);
            while next_sample as f64 * *dt <= t1 {
                let t = next_sample as f64 * *dt;
                let y = dense.eval(t);
                if gap(&y) <= 0.0 {
                    break;
                }
                trace.push(t, system.force(&y), gap(&y));
                next_sample += 1;
            }
        }
        if force_rate(&y_old) > 0.0 && force_rate(&y_new) <= 0.0 {
            let dense = ode.dense_output(&system);
            let t = find_root(
                |t| force_rate(&dense.eval(t)),
                t0,
                force_rate(&y_old),
                t1,
                force_rate(&y_new),
                1e-15 * t1.max(t_scale),
            );
            let f = system.force(&dense.eval(t));
            if f > peak.0 {
                peak = (f, t);
            }
        }
        if gap(&y_new) <= 0.0 && t1 > 0.0 {
            let dense = ode.dense_output(&system);
            let t_sep = find_root(
                |t| gap(&dense.eval(t)),
                t0,
                gap(&y_old),
                t1,
                gap(&y_new),
                1e-15 * t1.max(t_scale),
            );
            let y_sep = dense.eval(t_sep);
            if let Some((_, trace)) = record.as_mut() {
                trace.push(t_sep, 0.0, 0.0);
            }
            return Ok(ImpactOutcome::first_only(
                ContactEvent {
                    onset_s: 0.0,
                    peak_force_n: peak.0,
                    time_of_peak_s: peak.1,
                    duration_s: t_sep,
                },
                rate(&y_sep),
                (system.energy(&y0), system.energy(&y_sep)),
                ode.stats().rhs_evals,
            ));
        }
    }
}
