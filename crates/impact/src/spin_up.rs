//! The spin-up beam benchmark (Simo & Vu-Quoc 1986; Kane, Ryan & Banerjee 1987): a cantilever
//! clamped to a hub whose angle follows θ(t) = (ω_s/T_s)[t²/2 + (T_s/2π)²(cos(2πt/T_s) − 1)]
//! for t < T_s, then ω_s(t − T_s/2) ([`crate::drive::spin_up`]). Two beams by name: Simo &
//! Vu-Quoc's L = 10 m, A = 4e-4 m², I = 2e-7 m⁴, E = 7e10 Pa, ρ = 3000 kg/m³ (EA = 2.8e7 N,
//! EI = 1.4e4 N·m², ρA = 1.2 kg/m) ([`SpinUp::simo_vu_quoc`]), and Kane, Ryan & Banerjee's 8 m
//! aluminium beam ([`SpinUp::kane_ryan_banerjee`]); T_s = 15 s, ω_s = 4 or 6 rad/s. It shows why a link in large overall motion
//! needs geometric stiffening: the beam's first bending frequency (3.80 rad/s) is below
//! ω_s = 6 rad/s, and a linear beam in the rotating frame, which keeps the centrifugal softening
//! −ρA θ̇² v but not the stiffening of the centrifugal tension, diverges.
//!
//! Three solutions, each a time series of the tip's transverse deflection in the hub frame:
//!
//! * **FE** ([`spin_up_fe`]): flexrig-beam's corotational elements on a rotating clamp
//!   ([`flexrig_beam::rotating_clamp`]), generalized-α.
//! * **Reference** ([`spin_up_reference`]), written from the equations and independent of the FE
//!   code: an inextensible elastica in the hub frame by the Ritz method on its section angle,
//!   ψ(s, t) = Σⱼ qⱼ(t) φⱼ(s), φⱼ = Pⱼ(2s/L − 1) − (−1)ʲ (Legendre polynomials, φⱼ(0) = 0),
//!   position r(s) = ∫₀ˢ (cos ψ, sin ψ) dσ. With the hub's rate Ω = θ̇ the acceleration in the
//!   hub frame is a = r̈ + 2θ̇ J ṙ + θ̈ J r − θ̇² r, J(x, y) = (−y, x), and Kane's equations
//!   Σⱼ Mᵢⱼ q̈ⱼ = −∫ ρA Tᵢ·(c + 2θ̇ J ṙ + θ̈ J r − θ̇² r) ds − EI Σⱼ Kᵢⱼ qⱼ with the partial
//!   velocities Tᵢ(s) = ∂r/∂qᵢ = ∫₀ˢ (−sin ψ, cos ψ) φᵢ dσ, Mᵢⱼ = ∫ ρA Tᵢ·Tⱼ ds,
//!   c(s) = −∫₀ˢ (cos ψ, sin ψ) ψ̇² dσ, Kᵢⱼ = ∫ φᵢ′ φⱼ′ ds. The exact kinematics keep every
//!   geometric term (the stiffening is the x-part of −θ̇² r against the x-part of Tᵢ). Integrals
//!   by composite Gauss–Legendre, the running integrals by each panel's interpolating polynomial;
//!   solved by DOP853 (flexrig-lumped). Extension (EA) is left out: the centrifugal strain is
//!   ρA ω_s² L²/(2EA) ≤ 7.7e-5.
//! * **Linear** ([`spin_up_linear`]): the same Ritz basis with linearised kinematics,
//!   ρA (v̈ + θ̈ s − θ̇² v) + EI v'''' = 0: the known failure.

use std::sync::atomic::{AtomicBool, Ordering};

use flexrig_beam::rotating_clamp::{RotatingClampOptions, run_rotating_clamp_until};
use flexrig_beam::{BeamModel, BeamSpec, Kinematics, Section};
use flexrig_lumped::ode::dop853::{Dop853, Dop853Options, OdeSystem};
use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};

use crate::ImpactError;
use crate::drive::{positive, spin_up};

/// Kane, Ryan & Banerjee's (1987) aluminium: Young's modulus \[Pa\] (1e7 psi).
pub const KANE_E: f64 = 6.8952e10;
/// Kane, Ryan & Banerjee's density \[kg/m³\].
pub const KANE_RHO: f64 = 2766.67;
/// Kane, Ryan & Banerjee's cross-section area \[m²\].
pub const KANE_AREA: f64 = 7.2968e-5;
/// Kane, Ryan & Banerjee's second moment of area \[m⁴\].
pub const KANE_I: f64 = 8.2189e-9;

/// The beam and the spin-up.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpinUp {
    /// Length L \[m\].
    pub length: f64,
    /// Axial stiffness EA \[N\] (the FE beam; the reference is inextensible).
    pub ea: f64,
    /// Bending stiffness EI [N·m²].
    pub ei: f64,
    /// Mass per length ρA \[kg/m\].
    pub rho_a: f64,
    /// Final hub speed ω_s [rad/s].
    pub omega_s: f64,
    /// Spin-up time T_s \[s\].
    pub t_s: f64,
    /// End of the run \[s\] (the benchmark: T_s + 5 s).
    pub t_end: f64,
    /// Reporting interval \[s\].
    pub sample_every: f64,
}

impl SpinUp {
    /// The 10 m beam of Simo & Vu-Quoc (1986, "On the dynamics of flexible beams under large
    /// overall motions — the plane case", Part II, J. Appl. Mech. 53: 855–863): L = 10 m,
    /// EA = 2.8e7 N, EI = 1.4e4 N·m², ρA = 1.2 kg/m (E = 7e10 Pa, A = 4e-4 m², I = 2e-7 m⁴,
    /// ρ = 3000 kg/m³), T_s = 15 s, run to 20 s, reported every 0.1 s, at `omega_s` (4 rad/s
    /// as the case is usually reproduced; flexrig's default 6 rad/s is past the first bending
    /// frequency 3.80 rad/s, where the linear beam fails). Often credited to Kane et al., whose
    /// beam is [`SpinUp::kane_ryan_banerjee`]. (Parameters as the later literature quotes
    /// them; not checked against the original paper here.)
    pub fn simo_vu_quoc(omega_s: f64) -> SpinUp {
        SpinUp {
            length: 10.0,
            ea: 7e10 * 4e-4,
            ei: 7e10 * 2e-7,
            rho_a: 3000.0 * 4e-4,
            omega_s,
            t_s: 15.0,
            t_end: 20.0,
            sample_every: 0.1,
        }
    }

    /// The 8 m aluminium beam of Kane, Ryan & Banerjee (1987, "Dynamics of a cantilever beam
    /// attached to a moving base", J. Guidance 10(2): 139–151): L = 8 m,
    /// E = 6.8952e10 Pa, ρ = 2766.67 kg/m³, A = 7.2968e-5 m², I = 8.2189e-9 m⁴
    /// (EI = 566.7 N·m², ρA = 0.20188 kg/m; first bending frequency 2.91 rad/s), T_s = 15 s,
    /// run to 20 s, reported every 0.1 s, at `omega_s` (4 rad/s as the case is usually
    /// reproduced: past the first frequency, so the linear beam fails). (Parameters as the
    /// later literature quotes them; not checked against the original paper here.)
    pub fn kane_ryan_banerjee(omega_s: f64) -> SpinUp {
        SpinUp {
            length: 8.0,
            ea: KANE_E * KANE_AREA,
            ei: KANE_E * KANE_I,
            rho_a: KANE_RHO * KANE_AREA,
            omega_s,
            t_s: 15.0,
            t_end: 20.0,
            sample_every: 0.1,
        }
    }

    /// Checks the fields; the error names them.
    pub fn validate(&self) -> Result<(), ImpactError> {
        positive("length", self.length, 1e4, "m")?;
        positive("ea", self.ea, 1e15, "N")?;
        positive("ei", self.ei, 1e15, "N·m²")?;
        positive("rho_a", self.rho_a, 1e6, "kg/m")?;
        if !(self.omega_s.is_finite() && self.omega_s.abs() <= 1e3) {
            return Err(ImpactError::invalid(
                "omega_s",
                self.omega_s,
                "a finite speed within ±1e3 rad/s",
            ));
        }
        positive("t_s", self.t_s, 1e6, "s")?;
        positive("t_end", self.t_end, 1e6, "s")?;
        positive("sample_every", self.sample_every, self.t_end, "s")
    }

    /// (θ, θ̇, θ̈) of the hub at `t`.
    pub fn hub(&self, t: f64) -> [f64; 3] {
        let (a, b, c) = spin_up(self.omega_s, self.t_s, t);
        [a, b, c]
    }

    fn sample_times(&self) -> Vec<f64> {
        let n = (self.t_end / self.sample_every + 1e-9).floor() as usize;
        (0..=n).map(|k| k as f64 * self.sample_every).collect()
    }
}

/// A time series of the tip's transverse deflection in the hub frame.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpinUpSeries {
    /// Times \[s\].
    pub t: Vec<f64>,
    /// Tip deflection in the hub frame \[m\] (positive along the hub frame's y, ahead of the
    /// rotation).
    pub tip_deflection_m: Vec<f64>,
}

impl SpinUpSeries {
    /// Largest |deflection| \[m\].
    pub fn max_abs(&self) -> f64 {
        self.tip_deflection_m
            .iter()
            .fold(0.0, |m: f64, d| m.max(d.abs()))
    }

    /// Largest difference from `other` at the common times, over the largest |deflection| of
    /// `other`.
    pub fn difference(&self, other: &SpinUpSeries) -> f64 {
        let worst = self
            .tip_deflection_m
            .iter()
            .zip(&other.tip_deflection_m)
            .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
        worst / other.max_abs()
    }
}

/// The FE solution: `elements` corotational elements, steps of at most `max_step` \[s\],
/// generalized-α at ρ∞ = 0.9.
pub fn spin_up_fe(
    spec: &SpinUp,
    elements: usize,
    max_step: f64,
) -> Result<SpinUpSeries, ImpactError> {
    spin_up_fe_until(spec, elements, max_step, &AtomicBool::new(false))
}

/// [`spin_up_fe`], stopping with [`ImpactError::Interrupted`] once `stop` is set (looked at
/// every step).
pub fn spin_up_fe_until(
    spec: &SpinUp,
    elements: usize,
    max_step: f64,
    stop: &AtomicBool,
) -> Result<SpinUpSeries, ImpactError> {
    spec.validate()?;
    if !(1..=10_000).contains(&elements) {
        return Err(ImpactError::invalid(
            "elements",
            elements,
            "must lie in [1, 10000]",
        ));
    }
    positive("max_step", max_step, spec.sample_every, "s")?;
    let section = Section::from_stiffness(spec.ea, spec.ei, spec.rho_a)?;
    let model = BeamModel::new(BeamSpec::cantilever(
        spec.length,
        section,
        elements,
        Kinematics::Corotational,
    ))?;
    let options = RotatingClampOptions {
        max_step,
        ..RotatingClampOptions::DEFAULT
    };
    let hub = |t: f64| spec.hub(t);
    let samples =
        run_rotating_clamp_until(&model, &hub, spec.t_end, spec.sample_every, &options, stop)?;
    if stop.load(Ordering::Relaxed) {
        return Err(ImpactError::Interrupted);
    }
    Ok(SpinUpSeries {
        t: samples.iter().map(|s| s.t).collect(),
        tip_deflection_m: samples.iter().map(|s| s.tip_transverse_m).collect(),
    })
}

/// The independent reference (module docs): the inextensible elastica by `modes` Legendre
/// angle functions (2 to 12), DOP853 at relative tolerance `rtol`.
pub fn spin_up_reference(
    spec: &SpinUp,
    modes: usize,
    rtol: f64,
) -> Result<SpinUpSeries, ImpactError> {
    ritz(spec, modes, rtol, false, &AtomicBool::new(false))
}

/// [`spin_up_reference`], stopping with [`ImpactError::Interrupted`] once `stop` is set
/// (looked at every step).
pub fn spin_up_reference_until(
    spec: &SpinUp,
    modes: usize,
    rtol: f64,
    stop: &AtomicBool,
) -> Result<SpinUpSeries, ImpactError> {
    ritz(spec, modes, rtol, false, stop)
}

/// The linear beam in the rotating frame (no geometric stiffening), same basis.
pub fn spin_up_linear(spec: &SpinUp, modes: usize, rtol: f64) -> Result<SpinUpSeries, ImpactError> {
    ritz(spec, modes, rtol, true, &AtomicBool::new(false))
}

/// [`spin_up_linear`], stopping with [`ImpactError::Interrupted`] once `stop` is set.
pub fn spin_up_linear_until(
    spec: &SpinUp,
    modes: usize,
    rtol: f64,
    stop: &AtomicBool,
) -> Result<SpinUpSeries, ImpactError> {
    ritz(spec, modes, rtol, true, stop)
}

fn ritz(
    spec: &SpinUp,
    modes: usize,
    rtol: f64,
    linear: bool,
    stop: &AtomicBool,
) -> Result<SpinUpSeries, ImpactError> {
    spec.validate()?;
    if !(rtol.is_finite() && (1e-14..=1e-3).contains(&rtol)) {
        return Err(ImpactError::invalid(
            "rtol",
            rtol,
            "must lie in [1e-14, 1e-3]",
        ));
    }
    match modes {
        2 => run_ritz::<4>(spec, rtol, linear, stop),
        3 => run_ritz::<6>(spec, rtol, linear, stop),
        4 => run_ritz::<8>(spec, rtol, linear, stop),
        5 => run_ritz::<10>(spec, rtol, linear, stop),
        6 => run_ritz::<12>(spec, rtol, linear, stop),
        7 => run_ritz::<14>(spec, rtol, linear, stop),
        8 => run_ritz::<16>(spec, rtol, linear, stop),
        9 => run_ritz::<18>(spec, rtol, linear, stop),
        10 => run_ritz::<20>(spec, rtol, linear, stop),
        11 => run_ritz::<22>(spec, rtol, linear, stop),
        12 => run_ritz::<24>(spec, rtol, linear, stop),
        _ => Err(ImpactError::invalid("modes", modes, "must lie in [2, 12]")),
    }
}

/// Gauss–Legendre nodes and weights on [−1, 1] (Newton on Pₙ from Chebyshev guesses).
fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
    let mut x = vec![0.0; n];
    let mut w = vec![0.0; n];
    for i in 0..n {
        let mut z = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        for _ in 0..100 {
            let (p, dp) = legendre(n, z);
            let dz = p / dp;
            z -= dz;
            if dz.abs() < 1e-16 {
                break;
            }
        }
        let (_, dp) = legendre(n, z);
        x[i] = -z;
        w[i] = 2.0 / ((1.0 - z * z) * dp * dp);
    }
    (x, w)
}

/// (Pₙ(x), Pₙ′(x)).
fn legendre(n: usize, x: f64) -> (f64, f64) {
    let (mut p0, mut p1) = (1.0, x);
    let (mut d0, mut d1) = (0.0, 1.0);
    if n == 0 {
        return (1.0, 0.0);
    }
    for j in 1..n {
        let jf = j as f64;
        let p2 = ((2.0 * jf + 1.0) * x * p1 - jf * p0) / (jf + 1.0);
        let d2 = d0 + (2.0 * jf + 1.0) * p1;
        (p0, p1) = (p1, p2);
        (d0, d1) = (d1, d2);
    }
    (p1, d1)
}

/// Quadrature on [0, L]: `panels` panels of `order` Gauss points, with each node's running
/// integral ∫₀ˢ by its panel's interpolating polynomial.
struct Quadrature {
    s: Vec<f64>,
    w: Vec<f64>,
    order: usize,
    /// within[g][m] = ∫_{a}^{s_g} ℓ_m ds on a panel (ℓ_m the Lagrange basis of its nodes).
    within: Vec<Vec<f64>>,
}

impl Quadrature {
    fn new(length: f64, panels: usize, order: usize) -> Quadrature {
        let (x, wx) = gauss_legendre(order);
        let half = 0.5 * length / panels as f64;
        let mut s = Vec::new();
        let mut w = Vec::new();
        for p in 0..panels {
            let mid = (2 * p + 1) as f64 * half;
            for g in 0..order {
                s.push(mid + half * x[g]);
                w.push(half * wx[g]);
            }
        }
        let lagrange = |m: usize, xi: f64| {
            (0..order)
                .filter(|&k| k != m)
                .fold(1.0, |acc, k| acc * (xi - x[k]) / (x[m] - x[k]))
        };
        let within = (0..order)
            .map(|g| {
                // ∫_{−1}^{x_g} ℓ_m dξ by the same rule mapped onto [−1, x_g] (exact: degree < n)
                let h = 0.5 * (x[g] + 1.0);
                (0..order)
                    .map(|m| {
                        (0..order)
                            .map(|k| h * wx[k] * lagrange(m, -1.0 + h * (x[k] + 1.0)))
                            .sum::<f64>()
                            * half
                    })
                    .collect()
            })
            .collect();
        Quadrature {
            s,
            w,
            order,
            within,
        }
    }

    /// Running integrals ∫₀^{s_k} g at every node, for the node values `g`.
    fn running(&self, g: &[f64], out: &mut [f64]) {
        let mut before = 0.0;
        for (p, chunk) in g.chunks(self.order).enumerate() {
            let base = p * self.order;
            let mut full = 0.0;
            for (k, gk) in chunk.iter().enumerate() {
                out[base + k] = before
                    + self.within[k]
                        .iter()
                        .zip(chunk)
                        .map(|(a, b)| a * b)
                        .sum::<f64>();
                full += self.w[base + k] * gk;
            }
            before += full;
        }
    }
}

/// Buffers of [`Elastica::accelerations`], reused between calls (one run, one thread).
#[derive(Default)]
struct Scratch {
    psi: Vec<f64>,
    psid: Vec<f64>,
    sin: Vec<f64>,
    cos: Vec<f64>,
    g: Vec<f64>,
    rx: Vec<f64>,
    ry: Vec<f64>,
    vx: Vec<f64>,
    vy: Vec<f64>,
    cx: Vec<f64>,
    cy: Vec<f64>,
    ex: Vec<f64>,
    ey: Vec<f64>,
    tx: Vec<Vec<f64>>,
    ty: Vec<Vec<f64>>,
}

impl Scratch {
    fn resize(&mut self, nodes: usize, modes: usize) {
        for v in [
            &mut self.psi,
            &mut self.psid,
            &mut self.sin,
            &mut self.cos,
            &mut self.g,
            &mut self.rx,
            &mut self.ry,
            &mut self.vx,
            &mut self.vy,
            &mut self.cx,
            &mut self.cy,
            &mut self.ex,
            &mut self.ey,
        ] {
            v.resize(nodes, 0.0);
        }
        for t in [&mut self.tx, &mut self.ty] {
            t.resize(modes, Vec::new());
            for v in t.iter_mut() {
                v.resize(nodes, 0.0);
            }
        }
    }
}

struct Elastica {
    scratch: std::cell::RefCell<Scratch>,
    spec: SpinUp,
    modes: usize,
    quad: Quadrature,
    /// φⱼ at the nodes, [j][k].
    phi: Vec<Vec<f64>>,
    /// Kᵢⱼ = ∫ φᵢ′ φⱼ′ ds.
    k: DMatrix<f64>,
    linear: bool,
    /// Φⱼ(s) = ∫₀ˢ φⱼ (the linear model's shapes), [j][k].
    big_phi: Vec<Vec<f64>>,
}

impl Elastica {
    fn new(spec: &SpinUp, modes: usize, linear: bool) -> Elastica {
        // polynomials of degree ≤ 12 and smooth trigonometric integrands: 8 panels of 6 points
        // (24 panels of 8 change the series by < 1e-10 of its maximum)
        let quad = Quadrature::new(spec.length, 8, 6);
        let l = spec.length;
        let basis = |j: usize, s: f64| {
            let (p, dp) = legendre(j, 2.0 * s / l - 1.0);
            let sign = if j.is_multiple_of(2) { 1.0 } else { -1.0 };
            (p - sign, dp * 2.0 / l)
        };
        let nodes = quad.s.len();
        let phi: Vec<Vec<f64>> = (1..=modes)
            .map(|j| quad.s.iter().map(|&s| basis(j, s).0).collect())
            .collect();
        let dphi: Vec<Vec<f64>> = (1..=modes)
            .map(|j| quad.s.iter().map(|&s| basis(j, s).1).collect())
            .collect();
        let k = DMatrix::from_fn(modes, modes, |i, j| {
            (0..nodes)
                .map(|n| quad.w[n] * dphi[i][n] * dphi[j][n])
                .sum()
        });
        let mut big_phi = vec![vec![0.0; nodes]; modes];
        for j in 0..modes {
            quad.running(&phi[j], &mut big_phi[j]);
        }
        Elastica {
            scratch: std::cell::RefCell::new(Scratch::default()),
            spec: *spec,
            modes,
            quad,
            phi,
            k,
            linear,
            big_phi,
        }
    }

    /// (q̈, tip deflection in the hub frame) for (q, q̇) at t.
    fn accelerations(&self, t: f64, q: &[f64], qd: &[f64]) -> (DVector<f64>, f64) {
        let nodes = self.quad.s.len();
        let m = self.modes;
        let [_, w, al] = self.spec.hub(t);
        let (rho_a, ei) = (self.spec.rho_a, self.spec.ei);
        let mut mass = DMatrix::zeros(m, m);
        let mut f = DVector::zeros(m);
        let mut tip = 0.0;
        if self.linear {
            let v: Vec<f64> = (0..nodes)
                .map(|n| (0..m).map(|j| q[j] * self.big_phi[j][n]).sum())
                .collect();
            for i in 0..m {
                for j in 0..m {
                    mass[(i, j)] = rho_a
                        * (0..nodes)
                            .map(|n| self.quad.w[n] * self.big_phi[i][n] * self.big_phi[j][n])
                            .sum::<f64>();
                }
                f[i] = -rho_a
                    * (0..nodes)
                        .map(|n| {
                            self.quad.w[n]
                                * self.big_phi[i][n]
                                * (al * self.quad.s[n] - w * w * v[n])
                        })
                        .sum::<f64>();
            }
            for n in 0..nodes {
                let psi: f64 = (0..m).map(|j| q[j] * self.phi[j][n]).sum();
                tip += self.quad.w[n] * psi;
            }
        } else {
            // the same operations as before, into buffers reused between calls
            let mut guard = self.scratch.borrow_mut();
            let sc = &mut *guard;
            sc.resize(nodes, m);
            for n in 0..nodes {
                sc.psi[n] = (0..m).map(|j| q[j] * self.phi[j][n]).sum();
                sc.psid[n] = (0..m).map(|j| qd[j] * self.phi[j][n]).sum();
                let (sn, cs) = sc.psi[n].sin_cos();
                sc.sin[n] = sn;
                sc.cos[n] = cs;
            }
            let quad = &self.quad;
            let run = |g: &mut Vec<f64>, out: &mut Vec<f64>, f: &dyn Fn(usize) -> f64| {
                for (n, x) in g.iter_mut().enumerate() {
                    *x = f(n);
                }
                quad.running(g, out);
            };
            let (sin, cos, psid) = (&sc.sin, &sc.cos, &sc.psid);
            run(&mut sc.g, &mut sc.rx, &|n| cos[n]);
            run(&mut sc.g, &mut sc.ry, &|n| sin[n]);
            run(&mut sc.g, &mut sc.vx, &|n| -sin[n] * psid[n]);
            run(&mut sc.g, &mut sc.vy, &|n| cos[n] * psid[n]);
            run(&mut sc.g, &mut sc.cx, &|n| -cos[n] * psid[n] * psid[n]);
            run(&mut sc.g, &mut sc.cy, &|n| -sin[n] * psid[n] * psid[n]);
            for i in 0..m {
                let phi = &self.phi[i];
                run(&mut sc.g, &mut sc.tx[i], &|n| -sin[n] * phi[n]);
                run(&mut sc.g, &mut sc.ty[i], &|n| cos[n] * phi[n]);
            }
            let (rx, ry, vx, vy, cx, cy) = (&sc.rx, &sc.ry, &sc.vx, &sc.vy, &sc.cx, &sc.cy);
            let (tx, ty) = (&sc.tx, &sc.ty);
            // e = c + 2θ̇ J ṙ + θ̈ J r − θ̇² r, J(x, y) = (−y, x)
            for n in 0..nodes {
                sc.ex[n] = cx[n] - 2.0 * w * vy[n] - al * ry[n] - w * w * rx[n];
                sc.ey[n] = cy[n] + 2.0 * w * vx[n] + al * rx[n] - w * w * ry[n];
            }
            let (ex, ey) = (&sc.ex, &sc.ey);
            for i in 0..m {
                for j in i..m {
                    let v = rho_a
                        * (0..nodes)
                            .map(|n| self.quad.w[n] * (tx[i][n] * tx[j][n] + ty[i][n] * ty[j][n]))
                            .sum::<f64>();
                    mass[(i, j)] = v;
                    mass[(j, i)] = v;
                }
                f[i] = -rho_a
                    * (0..nodes)
                        .map(|n| self.quad.w[n] * (tx[i][n] * ex[n] + ty[i][n] * ey[n]))
                        .sum::<f64>();
            }
            let sin = &sc.sin;
            tip = (0..nodes).map(|n| self.quad.w[n] * sin[n]).sum();
        }
        let qv = DVector::from_column_slice(q);
        f -= &self.k * qv * ei;
        let acc = mass
            .cholesky()
            .map(|c| c.solve(&f))
            .unwrap_or_else(|| DVector::from_element(m, f64::NAN));
        (acc, tip)
    }
}

struct RitzSystem<'a, const N: usize>(&'a Elastica);

impl<const N: usize> OdeSystem<N> for RitzSystem<'_, N> {
    fn rhs(&self, t: f64, y: &[f64; N]) -> [f64; N] {
        let m = N / 2;
        let (acc, _) = self.0.accelerations(t, &y[..m], &y[m..]);
        std::array::from_fn(|i| if i < m { y[m + i] } else { acc[i - m] })
    }
}

fn run_ritz<const N: usize>(
    spec: &SpinUp,
    rtol: f64,
    linear: bool,
    stop: &AtomicBool,
) -> Result<SpinUpSeries, ImpactError> {
    let m = N / 2;
    let model = Elastica::new(spec, m, linear);
    let system = RitzSystem::<N>(&model);
    let options = Dop853Options {
        rtol,
        atol: [rtol * 1e-3; N],
        first_step: None,
        max_step: spec.sample_every,
        max_steps: 50_000_000,
    };
    let mut ode = Dop853::new(&system, 0.0, [0.0; N], options);
    let mut series = SpinUpSeries {
        t: Vec::new(),
        tip_deflection_m: Vec::new(),
    };
    let mut stops = spec.sample_times();
    if spec.t_s < spec.t_end && !stops.contains(&spec.t_s) {
        stops.push(spec.t_s);
        stops.sort_by(f64::total_cmp);
    }
    let what = if linear {
        "spin-up linear model"
    } else {
        "spin-up reference"
    };
    for &t in &stops {
        // A step capped at max_step can end a rounding error short of the stop (the stops are
        // k × sample_every, their spacing not exactly sample_every): a remainder within a few
        // ulps of t is no step (the integrator refuses it), the state is the one at t.
        while ode.t() < t && t - ode.t() > 8.0 * f64::EPSILON * t.abs() {
            if stop.load(Ordering::Relaxed) {
                return Err(ImpactError::Interrupted);
            }
            ode.step_until(&system, t)
                .map_err(|e| ImpactError::Unfinished {
                    what,
                    reason: e.to_string(),
                })?;
        }
        let y = *ode.y();
        let (_, tip) = model.accelerations(t, &y[..m], &y[m..]);
        if ((t / spec.sample_every).round() * spec.sample_every - t).abs() <= 1e-9 * spec.t_end {
            series.t.push(t);
            series.tip_deflection_m.push(tip);
        }
    }
    Ok(series)
}
