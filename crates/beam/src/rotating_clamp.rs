//! A beam clamped to a hub whose angle θ(t) is prescribed (a rotating clamp): the spin-up beam
//! benchmark (Kane, Ryan & Banerjee 1987; Simo & Vu-Quoc 1986) and any robot link whose joint
//! follows a trajectory.
//!
//! The root node's DOFs are held at (u, v, θ) = (0, 0, θ(t)), its rate at (0, 0, θ̇(t)) and its
//! acceleration at (0, 0, θ̈(t)); the free DOFs follow the generalized-α scheme of
//! [`crate::dynamics`] (Arnold & Brüls' form, Chung–Hulbert parameters from ρ∞) with the residual
//! r(q, q̇, q̈) = f_int + f_in of [`crate::assembly`] evaluated with the prescribed root values,
//! so the hub's motion drives the beam through the element forces and the inertia coupling. The
//! corotational element keeps the geometric stiffening (the centrifugal tension stiffens the
//! bending) that a linear beam in a rotating frame lacks. The constrained row of θ₀ holds the
//! torque the hub must apply.
//!
//! The tip's deflection is reported in the hub frame: with the tip at p = (L + u_N, v_N),
//! d = −sin θ p_x + cos θ p_y (transverse) and a = cos θ p_x + sin θ p_y − L (axial).

use crate::BeamError;
use crate::assembly::{JacobianWeights, Kinematic, assemble, band_for};
use crate::model::BeamModel;

/// Settings of the integration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RotatingClampOptions {
    /// Largest time step \[s\] (the step is shortened so that samples fall on steps).
    pub max_step: f64,
    /// Spectral radius at infinite frequency ρ∞ ∈ [0, 1] (1: no numerical dissipation).
    pub rho_inf: f64,
    /// Newton converged when no correction exceeds this × L.
    pub newton_tolerance: f64,
    /// Most Newton iterations per step.
    pub max_iterations: usize,
}

impl RotatingClampOptions {
    /// Step 1e-3 s, ρ∞ = 0.9, Newton to 1e-12 L in at most 30 iterations.
    pub const DEFAULT: RotatingClampOptions = RotatingClampOptions {
        max_step: 1e-3,
        rho_inf: 0.9,
        newton_tolerance: 1e-12,
        max_iterations: 30,
    };
}

/// The beam's tip in the hub frame at one instant.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct HubFrameSample {
    /// Time \[s\].
    pub t: f64,
    /// Hub angle θ \[rad\].
    pub hub_angle: f64,
    /// Transverse tip deflection in the hub frame \[m\].
    pub tip_transverse_m: f64,
    /// Axial tip displacement in the hub frame \[m\].
    pub tip_axial_m: f64,
    /// Torque the hub applies to the beam [N·m].
    pub hub_torque_nm: f64,
}

/// Runs `model` (clamped root, corotational elements) with its hub at `hub(t)` = (θ \[rad\],
/// θ̇ [rad/s], θ̈ [rad/s²]) from t = 0 (in rigid rotation with the hub, undeformed) to `t_end`,
/// and samples the tip every `sample_every` seconds (t = 0 included).
pub fn run_rotating_clamp(
    model: &BeamModel,
    hub: &dyn Fn(f64) -> [f64; 3],
    t_end: f64,
    sample_every: f64,
    options: &RotatingClampOptions,
) -> Result<Vec<HubFrameSample>, BeamError> {
    let never = std::sync::atomic::AtomicBool::new(false);
    run_rotating_clamp_until(model, hub, t_end, sample_every, options, &never)
}

/// [`run_rotating_clamp`], returning early (with the samples so far) once `stop` is set: the
/// caller tells a stopped run from a finished one by the flag (looked at every step).
pub fn run_rotating_clamp_until(
    model: &BeamModel,
    hub: &dyn Fn(f64) -> [f64; 3],
    t_end: f64,
    sample_every: f64,
    options: &RotatingClampOptions,
    stop: &std::sync::atomic::AtomicBool,
) -> Result<Vec<HubFrameSample>, BeamError> {
    crate::dynamics::check_rotating_clamp(model)?;
    if !(t_end.is_finite() && t_end > 0.0) {
        return Err(BeamError::invalid("t_end", t_end, "a finite time > 0 s"));
    }
    if !(sample_every.is_finite() && sample_every > 0.0 && sample_every <= t_end) {
        return Err(BeamError::invalid(
            "sample_every",
            sample_every,
            "a time in (0, t_end] s",
        ));
    }
    if !(options.max_step.is_finite() && options.max_step > 0.0) {
        return Err(BeamError::invalid(
            "max_step",
            options.max_step,
            "a finite step > 0 s",
        ));
    }
    if !(0.0..=1.0).contains(&options.rho_inf) {
        return Err(BeamError::invalid(
            "rho_inf",
            options.rho_inf,
            "a number in [0, 1]",
        ));
    }
    let steps_per_sample = (sample_every / options.max_step).ceil().max(1.0) as usize;
    let h = sample_every / steps_per_sample as f64;
    let samples = (t_end / sample_every + 1e-9).floor() as usize;
    let rho = options.rho_inf;
    let am = (2.0 * rho - 1.0) / (rho + 1.0);
    let af = rho / (rho + 1.0);
    let g = 0.5 - am + af;
    let b = 0.25 * (1.0 - am + af).powi(2);
    let n = model.n_dofs();
    let nfix = model.n_fixed();
    let l = model.length();
    let tip = model.tip_node();
    // t = 0: rigid rotation with the hub
    let [th0, w0, al0] = hub(0.0);
    let mut q = vec![0.0; n];
    let mut v = vec![0.0; n];
    let mut a = vec![0.0; n];
    for i in 0..=tip {
        let x = model.node_x(i);
        let (s, c) = th0.sin_cos();
        q[3 * i] = x * (c - 1.0);
        q[3 * i + 1] = x * s;
        q[3 * i + 2] = th0;
        v[3 * i] = -x * s * w0;
        v[3 * i + 1] = x * c * w0;
        v[3 * i + 2] = w0;
    }
    set_root(&mut q, &mut v, &mut a, [th0, w0, al0]);
    let f_ext = vec![0.0; 3 * model.n_nodes()];
    let mut r = vec![0.0; n];
    let mut band = band_for(model);
    // initial acceleration: M q̈_free = −r(q, q̇, q̈ with the free part 0)
    assemble(
        model,
        Kinematic {
            q: &q,
            v: Some(&v),
            a: Some(&a),
        },
        &f_ext,
        &mut r,
        Some((
            &mut band,
            JacobianWeights {
                stiffness: 0.0,
                velocity: 0.0,
                acceleration: 1.0,
            },
        )),
    );
    band.factorize("mass matrix")?;
    let mut rhs: Vec<f64> = r[nfix..].iter().map(|x| -x).collect();
    band.solve_in_place(&mut rhs);
    a[nfix..].copy_from_slice(&rhs);
    let mut ahat = a.clone();
    let mut out = Vec::with_capacity(samples + 1);
    out.push(sample(model, &q, &v, &a, &f_ext, 0.0, th0));
    let weights = JacobianWeights {
        stiffness: 1.0,
        velocity: g / (b * h),
        acceleration: (1.0 - am) / ((1.0 - af) * b * h * h),
    };
    let tol = options.newton_tolerance * l;
    let mut dq = vec![0.0; n];
    let mut q1 = q.clone();
    let mut v1 = v.clone();
    let mut a1 = a.clone();
    let mut ahat1 = ahat.clone();
    for k in 1..=samples * steps_per_sample {
        if stop.load(std::sync::atomic::Ordering::Relaxed) {
            return Ok(out);
        }
        let t1 = k as f64 * h;
        let root = hub(t1);
        if !root.iter().all(|x| x.is_finite()) {
            return Err(BeamError::NonFinite {
                what: format!("hub motion at t = {t1}"),
            });
        }
        // predictor: â_{n+1} = â_n
        for i in nfix..n {
            dq[i] = h * v[i] + h * h * 0.5 * ahat[i];
        }
        let mut converged = false;
        for _ in 0..options.max_iterations {
            for i in nfix..n {
                let ah = (dq[i] - h * v[i] - h * h * (0.5 - b) * ahat[i]) / (b * h * h);
                ahat1[i] = ah;
                q1[i] = q[i] + dq[i];
                v1[i] = v[i] + h * ((1.0 - g) * ahat[i] + g * ah);
                a1[i] = ((1.0 - am) * ah + am * ahat[i] - af * a[i]) / (1.0 - af);
            }
            set_root(&mut q1, &mut v1, &mut a1, root);
            assemble(
                model,
                Kinematic {
                    q: &q1,
                    v: Some(&v1),
                    a: Some(&a1),
                },
                &f_ext,
                &mut r,
                Some((&mut band, weights)),
            );
            band.factorize("generalized-α iteration matrix")?;
            let mut corr: Vec<f64> = r[nfix..].iter().map(|x| -x).collect();
            band.solve_in_place(&mut corr);
            let s = crate::statics::rotation_limiter(&corr, nfix);
            let mut largest = 0.0_f64;
            for (i, c) in (nfix..n).zip(&corr) {
                dq[i] += s * c;
                largest = largest.max((s * c).abs());
            }
            if !largest.is_finite() {
                return Err(BeamError::NonFinite {
                    what: format!("rotating-clamp step at t = {t1}"),
                });
            }
            if largest <= tol {
                converged = true;
                break;
            }
        }
        if !converged {
            return Err(BeamError::NotConverged {
                solver: format!("rotating-clamp step at t = {t1:.6e} s (h = {h:.3e} s)"),
                load_level: 1.0,
                iterations: options.max_iterations,
                residual: r[nfix..].iter().fold(0.0, |m, x| m.max(x.abs())),
            });
        }
        // the state at the converged increment
        for i in nfix..n {
            let ah = (dq[i] - h * v[i] - h * h * (0.5 - b) * ahat[i]) / (b * h * h);
            ahat1[i] = ah;
            q1[i] = q[i] + dq[i];
            v1[i] = v[i] + h * ((1.0 - g) * ahat[i] + g * ah);
            a1[i] = ((1.0 - am) * ah + am * ahat[i] - af * a[i]) / (1.0 - af);
        }
        set_root(&mut q1, &mut v1, &mut a1, root);
        std::mem::swap(&mut q, &mut q1);
        std::mem::swap(&mut v, &mut v1);
        std::mem::swap(&mut a, &mut a1);
        std::mem::swap(&mut ahat, &mut ahat1);
        if k % steps_per_sample == 0 {
            out.push(sample(model, &q, &v, &a, &f_ext, t1, root[0]));
        }
    }
    Ok(out)
}

fn set_root(q: &mut [f64], v: &mut [f64], a: &mut [f64], [th, w, al]: [f64; 3]) {
    q[..3].copy_from_slice(&[0.0, 0.0, th]);
    v[..3].copy_from_slice(&[0.0, 0.0, w]);
    a[..3].copy_from_slice(&[0.0, 0.0, al]);
}

fn sample(
    model: &BeamModel,
    q: &[f64],
    v: &[f64],
    a: &[f64],
    f_ext: &[f64],
    t: f64,
    theta: f64,
) -> HubFrameSample {
    let tip = model.tip_node();
    let px = model.length() + q[3 * tip];
    let py = q[3 * tip + 1];
    let (s, c) = theta.sin_cos();
    let mut r = vec![0.0; q.len()];
    assemble(
        model,
        Kinematic {
            q,
            v: Some(v),
            a: Some(a),
        },
        f_ext,
        &mut r,
        None,
    );
    HubFrameSample {
        t,
        hub_angle: theta,
        tip_transverse_m: -s * px + c * py,
        tip_axial_m: c * px + s * py - model.length(),
        hub_torque_nm: r[2],
    }
}
