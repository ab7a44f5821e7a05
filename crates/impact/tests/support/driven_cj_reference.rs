//! The independent solution of the driven CJ with the exact dome geometry (see
//! crates/impact/tests/driven_recontact.rs), written from the physics, not from the library:
//! a light link on a soft torsion spring, its hub turned at a constant speed ω, strikes a free
//! hand until the hand moves away beyond the dome's reach. Shared by flexrig-impact's tests
//! and flexrig's driven safety tests (included by path).
//!
//! In the joint angle φ of the link (φ_m = ω t the hub's prescribed angle):
//!   J φ̈ = k_θ (ω t − φ) − f L λ(u),   J = (m_e + m_r/3) L², k_θ = k_δ L²
//!   m_h Ẍ = f
//!   δ = L sin u + d_c (1 − cos u) − X,  λ = cos u + (d_c/L) sin u,  u = φ − φ_c
//!   f = k_c δⁿ (δ > 0)
//! with d_c = R − s the dome's centre behind the link's axis. Fixed-step RK4 at 2e-7 s; the
//! contacts are the stretches with δ > 0, their peaks the largest sampled force refined by a
//! parabola through the three samples around it.

#![allow(dead_code)]

use flexrig_contact::{DampingSpec, Hertz};
use flexrig_impact::DrivenStrike;
use flexrig_impact::LinkParams;
use flexrig_impact::drive::{
    Dome, Drive, DriveCommand, HeadSupport, Motor, Person, Placement, Profile,
};

pub const L: f64 = 0.5;
pub const M_R: f64 = 0.3;
pub const M_E: f64 = 0.02;
pub const K_DELTA: f64 = 2e3;
pub const M_H: f64 = 0.6;
pub const K_C: f64 = 1e6;
pub const N_C: f64 = 1.5;
pub const PHI_C: f64 = 0.05;

pub fn strike(omega: f64) -> DrivenStrike {
    strike_of(omega, M_R, M_E)
}

pub fn strike_of(omega: f64, m_r: f64, m_e: f64) -> DrivenStrike {
    DrivenStrike {
        link: LinkParams {
            m_r,
            length: L,
            k_delta: K_DELTA,
            m_e,
        },
        drive: Drive::new(
            Motor::new(0.0, 1.0, 0.0).unwrap(),
            DriveCommand::Trajectory {
                profile: Profile::Steady { speed: omega },
            },
        )
        .unwrap(),
        person: Person {
            m_h: M_H,
            support: HeadSupport::Free,
            contact: Hertz::new(K_C, N_C).unwrap(),
            damping: DampingSpec::NONE,
            speed: 0.0,
        },
        placement: Placement::Angle { angle: PHI_C },
        horizon_s: 5.0,
    }
}

/// (onset, peak force, time of peak, duration) of every contact by the reference, until the
/// hand is beyond the dome's reach and moving away, or `t_end`.
pub fn reference(omega: f64, t_end: f64) -> Vec<(f64, f64, f64, f64)> {
    reference_of(omega, t_end, M_E + M_R / 3.0, &Dome::TEST_BED)
}

/// [`reference`] for a link of inertia `m_lumped` L² about its hub and the dome `dome`.
pub fn reference_of(
    omega: f64,
    t_end: f64,
    m_lumped: f64,
    dome: &Dome,
) -> Vec<(f64, f64, f64, f64)> {
    reference_along(omega, t_end, m_lumped, Some(dome))
}

/// [`reference_of`] with the contact on the dome (`Some`), or along the linear models' straight
/// path (`None`): the tip at arc length L φ and the hand on the same line,
/// δ = L (φ − φ_c) − X, λ = 1, where the tip can always come back (no reach: to `t_end`).
pub fn reference_along(
    omega: f64,
    t_end: f64,
    m_lumped: f64,
    dome: Option<&Dome>,
) -> Vec<(f64, f64, f64, f64)> {
    let j = m_lumped * L * L;
    let k_theta = K_DELTA * L * L;
    let geometry = |phi: f64, x: f64| {
        let u = phi - PHI_C;
        match dome {
            Some(dome) => {
                let d_c = dome.radius_m - dome.standoff_m;
                let delta = L * u.sin() + d_c * (1.0 - u.cos()) - x;
                let lever = u.cos() + d_c / L * u.sin();
                (delta, lever)
            }
            None => (L * u - x, 1.0),
        }
    };
    let force = |delta: f64| {
        if delta > 0.0 {
            K_C * delta.powf(N_C)
        } else {
            0.0
        }
    };
    // state: φ, φ̇, X, Ẋ
    let rhs = |t: f64, s: [f64; 4]| {
        let (delta, lever) = geometry(s[0], s[2]);
        let f = force(delta);
        [
            s[1],
            (k_theta * (omega * t - s[0]) - f * L * lever) / j,
            s[3],
            f / M_H,
        ]
    };
    let h = 2e-7;
    let reach = dome.map_or(f64::INFINITY, |d| {
        let d_c = d.radius_m - d.standoff_m;
        L.hypot(d_c) + d_c
    });
    // the link turns steadily with its hub up to the contact: φ = ω t, no spring deflection
    let mut s = [0.0, omega, 0.0, 0.0];
    let mut t = 0.0;
    let mut contacts = Vec::new();
    let mut current: Option<(f64, Vec<(f64, f64)>)> = None;
    let mut prev_delta = geometry(s[0], s[2]).0;
    while t < t_end {
        let k1 = rhs(t, s);
        let add = |a: [f64; 4], k: [f64; 4], c: f64| std::array::from_fn(|i| a[i] + c * k[i]);
        let k2 = rhs(t + h / 2.0, add(s, k1, h / 2.0));
        let k3 = rhs(t + h / 2.0, add(s, k2, h / 2.0));
        let k4 = rhs(t + h, add(s, k3, h));
        s = std::array::from_fn(|i| s[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]));
        t += h;
        let delta = geometry(s[0], s[2]).0;
        if prev_delta <= 0.0 && delta > 0.0 {
            // onset by linear interpolation of δ over the step
            let onset = t - h * delta / (delta - prev_delta);
            current = Some((onset, Vec::new()));
        }
        if let Some((_, samples)) = current.as_mut() {
            samples.push((t, force(delta)));
        }
        if prev_delta > 0.0 && delta <= 0.0 {
            let end = t - h * delta / (delta - prev_delta);
            let (onset, samples) = current.take().unwrap();
            let i = (0..samples.len())
                .max_by(|a, b| samples[*a].1.total_cmp(&samples[*b].1))
                .unwrap();
            let (tp, fp) = if i > 0 && i + 1 < samples.len() {
                let (a, b, c) = (samples[i - 1], samples[i], samples[i + 1]);
                // vertex of the parabola through the three samples (equal spacing h)
                let den = a.1 - 2.0 * b.1 + c.1;
                let x = 0.5 * (a.1 - c.1) / den;
                (b.0 + x * h, b.1 - 0.25 * (a.1 - c.1) * x)
            } else {
                samples[i]
            };
            contacts.push((onset, fp, tp, end - onset));
        }
        prev_delta = delta;
        if current.is_none() && s[3] >= 0.0 && s[2] > reach {
            break;
        }
    }
    contacts
}
