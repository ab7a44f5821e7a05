//! A run's traces as arrays, for programs that analyse them in memory (the Python package):
//! a [`Recorder`] that collects every sensor sample and every step into columns.
//!
//! Two time bases:
//! - **samples**, at the scene's `record.sample_rate_hz` (the virtual sensors of
//!   [`flexrig_rig::sensors`]): force sensor, both accelerometers, both encoders, link tip
//!   deflection, and the contact indentation interpolated at the sample time linearly between
//!   step ends — the same interpolation the sensors use for the force;
//! - **steps**, one entry per integration step: its end time and size, the contact force and
//!   indentation at its end (0 outside contact) and the total mechanical energy.

use flexrig_contact::Materials;
use flexrig_rig::{
    Frame, Override, Recorder, RigError, RunOptions, RunSummary, Simulation, scene_with_overrides,
};

use crate::Error;
use crate::shared::cancel::CancelToken;

/// The sensor samples of a run as columns (one entry per sample, at the scene's sample rate).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SampleTraces {
    /// Sample time \[s\] (from 0, strictly increasing).
    pub time_s: Vec<f64>,
    /// Force sensor between load and dome \[N\].
    pub force_n: Vec<f64>,
    /// Contact indentation δ \[m\] (linear between step ends; 0 outside contact).
    pub indentation_m: Vec<f64>,
    /// Operator block accelerometer, along the strike direction [m/s²].
    pub operator_accel_mps2: Vec<f64>,
    /// Load accelerometer, along the strike direction [m/s²].
    pub load_accel_mps2: Vec<f64>,
    /// Operator encoder: pendulum angle from the vertical \[rad\].
    pub operator_angle_rad: Vec<f64>,
    /// Robot encoder: angle of the robot axis \[rad\] (0 for CL).
    pub robot_angle_rad: Vec<f64>,
    /// Lateral tip deflection of the link \[m\].
    pub link_tip_deflection_m: Vec<f64>,
}

/// The steps of a run as columns (one entry per integration step).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct StepTraces {
    /// Time at the end of the step \[s\].
    pub time_s: Vec<f64>,
    /// Step size \[s\].
    pub dt_s: Vec<f64>,
    /// Contact force at the end of the step \[N\] (0 outside contact).
    pub force_n: Vec<f64>,
    /// Contact indentation at the end of the step \[m\] (0 outside contact).
    pub indentation_m: Vec<f64>,
    /// Total mechanical energy \[J\].
    pub energy_j: Vec<f64>,
}

/// Both time bases of a run.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Traces {
    /// At the sensor sample rate.
    pub samples: SampleTraces,
    /// Per step.
    pub steps: StepTraces,
}

/// A recorder that collects [`Traces`]; stops the run (with [`RigError::Interrupted`]) at the
/// first step after its flag is set.
#[derive(Debug, Default)]
pub struct TraceRecorder {
    traces: Traces,
    cancel: CancelToken,
}

impl TraceRecorder {
    /// An empty recorder watching `cancel`.
    pub fn new(cancel: CancelToken) -> Self {
        TraceRecorder {
            cancel,
            ..Default::default()
        }
    }

    /// The traces collected.
    pub fn into_traces(self) -> Traces {
        self.traces
    }
}

impl Recorder for TraceRecorder {
    fn frame(&mut self, f: &Frame<'_>) -> Result<(), RigError> {
        if self.cancel.is_cancelled() {
            return Err(RigError::Interrupted { t: f.t });
        }
        let (force, indentation) = f.contact.map_or((0.0, 0.0), |c| (c.force, c.indentation));
        let s = &mut self.traces.samples;
        for sample in f.samples {
            s.time_s.push(sample.t);
            s.force_n.push(sample.force_n);
            s.indentation_m.push(sample.indentation_m);
            s.operator_accel_mps2.push(sample.operator_accel_mps2);
            s.load_accel_mps2.push(sample.load_accel_mps2);
            s.operator_angle_rad.push(sample.operator_angle_rad);
            s.robot_angle_rad.push(sample.robot_angle_rad);
            s.link_tip_deflection_m.push(sample.link_tip_deflection_m);
        }
        let st = &mut self.traces.steps;
        st.time_s.push(f.t);
        st.dt_s.push(f.dt);
        st.force_n.push(force);
        st.indentation_m.push(indentation);
        st.energy_j.push(f.energy);
        Ok(())
    }
}

/// Runs the scene `text` with `overrides` (validated like the file: an error names the field)
/// and returns its summary and traces; stops when `interrupt` is set.
pub fn run_traced(
    text: &str,
    overrides: &[Override],
    cancel: &CancelToken,
) -> Result<(RunSummary, Traces), Error> {
    let scene = scene_with_overrides(text, overrides, &Materials::bundled()?)?;
    let simulation = Simulation::new(&scene, RunOptions::default())?;
    let mut recorder = TraceRecorder::new(cancel.clone());
    let summary = simulation.run(&mut recorder)?;
    Ok((summary, recorder.into_traces()))
}

/// [`run_traced`], also logging the run as `log` asks (the MCAP file and its Foxglove layout, as
/// `flexrig run --out` writes them; [`crate::testbed::run::run_scene_file`]): the summary, the traces, and
/// the log finished either way.
pub fn run_traced_logged(
    text: &str,
    overrides: &[Override],
    log: crate::testbed::run::LogRequest<'_>,
    cancel: &CancelToken,
) -> Result<(RunSummary, Traces), Error> {
    let Some(out) = log.out else {
        return run_traced(text, overrides, cancel);
    };
    let scene = scene_with_overrides(text, overrides, &Materials::bundled()?)?;
    // the log records the scene as run
    let logged_text = flexrig_rig::overrides::apply(text, overrides)?;
    let simulation = Simulation::new(&scene, RunOptions::default())?;
    let mut recorder = TraceRecorder::new(cancel.clone());
    let summary = crate::log::file::run_logged_also(
        simulation,
        &scene,
        &crate::log::file::LogTarget {
            path: out,
            force: log.force,
            scene_text: &logged_text,
            cancel: cancel.clone(),
            rates: log.rates,
            deformation_scale: log.deformation_scale,
        },
        &mut recorder,
    )?;
    Ok((summary, recorder.into_traces()))
}

#[cfg(test)]
mod tests {
    use super::*;

    const SCENE: &str = include_str!("../../../../assets/scenes/cj_aluminium.toml");

    fn cancelled() -> CancelToken {
        let cancel = CancelToken::new();
        cancel.cancel();
        cancel
    }

    #[test]
    fn traces_hold_every_sample_and_step_of_the_run() {
        let (summary, traces) = run_traced(SCENE, &[], &CancelToken::new()).unwrap();
        let s = &traces.samples;
        assert_eq!(s.time_s.len(), summary.samples.len());
        for (i, sample) in summary.samples.iter().enumerate() {
            assert_eq!(s.time_s[i], sample.t);
            assert_eq!(s.force_n[i], sample.force_n);
            assert_eq!(s.load_accel_mps2[i], sample.load_accel_mps2);
        }
        assert_eq!(traces.steps.time_s.len(), summary.steps);
        assert!(s.time_s.windows(2).all(|w| w[1] > w[0]));
        // the sampled indentation and the steps' stay below the run's largest indentation (the
        // maximum between the steps, the adaptive contact's few steps included), the samples
        // within the variation over half a sample period (50 kHz in a 4.3 ms contact: 3e-5)
        let max_step = traces
            .steps
            .indentation_m
            .iter()
            .fold(0.0f64, |a, &b| a.max(b));
        let max_sample = s.indentation_m.iter().fold(0.0f64, |a, &b| a.max(b));
        let largest = summary.max_indentation_m * (1.0 + 1e-9);
        assert!(max_step <= largest, "{max_step} > {largest}");
        assert!(max_sample <= largest, "{max_sample} > {largest}");
        assert!(max_sample > (1.0 - 1e-4) * summary.max_indentation_m);
        // zero outside contact, positive inside
        let onset = summary.onset_time_s;
        for (t, d) in s.time_s.iter().zip(&s.indentation_m) {
            if *t < onset - 1e-6 {
                assert_eq!(*d, 0.0, "t = {t}");
            }
        }
    }

    #[test]
    fn a_logged_run_has_the_traces_of_an_unlogged_one_and_writes_its_log() {
        let dir = std::env::temp_dir().join(format!("flexrig-traced-log-{}", std::process::id()));
        let path = dir.join("run.mcap");
        let _ = std::fs::remove_dir_all(&dir);
        let log = crate::testbed::run::LogRequest {
            out: Some(&path),
            force: false,
            rates: crate::log::mcap::LogRates::DECIMATED,
            deformation_scale: 1.0,
        };
        let (summary, traces) = run_traced_logged(SCENE, &[], log, &CancelToken::new()).unwrap();
        let (plain, plain_traces) = run_traced(SCENE, &[], &CancelToken::new()).unwrap();
        assert_eq!(summary.peak_force_n.to_bits(), plain.peak_force_n.to_bits());
        assert_eq!(traces, plain_traces);
        assert!(std::fs::metadata(&path).unwrap().len() > 0);
        assert!(crate::log::layout::path_beside(&path).is_file());
        // the log is not replaced without force
        let again = run_traced_logged(SCENE, &[], log, &CancelToken::new()).unwrap_err();
        assert!(again.to_string().contains("--force"), "{again}");
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_set_interrupt_stops_the_run() {
        let e = run_traced(SCENE, &[], &cancelled()).unwrap_err();
        assert!(matches!(e, Error::Rig(RigError::Interrupted { .. })), "{e}");
    }

    #[test]
    fn a_bad_override_names_its_path() {
        let o = Override::new("robot.payload_kg", toml::Value::String("heavy".into()));
        let e = run_traced(SCENE, &[o], &CancelToken::new()).unwrap_err();
        assert!(e.to_string().contains("robot.payload_kg"), "{e}");
    }
}
