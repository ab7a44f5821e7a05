//! Lean sampling (`Simulation::with_lean_samples`): a run that computes the free swing's sensor
//! samples only where they are read must give the full run's numbers bit for bit — the summary,
//! every contact, the severity (peaks, pressures, energies, HIC) and every frame a recorder
//! gets — on every bundled test-bed scene (the reference is the same scene sampled in full, at
//! its own 50 kHz). And the severity computed over the contact stretches must be the whole
//! trace's maximum: the old computation over every sample agrees to round-off (its running
//! HIC integral starts 0.3 s earlier, so the last bits differ).

mod common;

use flexrig_rig::severity::of_samples;
use flexrig_rig::{
    Frame, NoRecorder, Recorder, RigError, RunOptions, RunSummary, Scene, Simulation, SwingSamples,
};

/// The bundled test-bed scenes (not the driven scenes of flexrig-impact).
const SCENES: [&str; 8] = [
    "cj_aluminium",
    "cj_iron",
    "cj_light_load",
    "cl_aluminium",
    "cl_iron",
    "cl_light_load",
    "rig_driven_cj",
    "rig_driven_cl",
];

/// Everything a recorder sees, as text (Debug prints every f64 exactly).
#[derive(Default)]
struct Frames {
    /// The recorder's choice of swing samples.
    choice: Option<SwingSamples>,
    /// Chooses every `n`th swing sample time it is asked about (a decimating log).
    every: usize,
    asked: usize,
    log: Vec<String>,
}

impl Recorder for Frames {
    fn frame(&mut self, f: &Frame<'_>) -> Result<(), RigError> {
        let samples: Vec<_> = if self.choice == Some(SwingSamples::Chosen) {
            Vec::new()
        } else {
            f.samples.to_vec()
        };
        self.log.push(format!(
            "{} {} {:?} {:?} {:?} {:?} {:?} {:?} {} {:?} {:?}",
            f.t,
            f.dt,
            f.outcome,
            f.operator,
            f.robot,
            f.operator_pose,
            f.dome_body_pose,
            f.contact,
            f.energy,
            f.drive,
            samples
        ));
        Ok(())
    }

    fn swing_samples(&self) -> SwingSamples {
        self.choice.unwrap_or(SwingSamples::Every)
    }

    fn wants_swing_sample(&mut self, _t: f64) -> bool {
        self.asked += 1;
        (self.asked - 1).is_multiple_of(self.every.max(1))
    }
}

fn run(scene: &Scene, lean: bool, recorder: &mut dyn Recorder) -> RunSummary {
    let sim = Simulation::new(scene, RunOptions::default()).unwrap();
    let sim = if lean { sim.with_lean_samples() } else { sim };
    sim.run(recorder).unwrap()
}

/// The summary without its samples, every number exact.
fn numbers(s: &RunSummary) -> String {
    let mut s = s.clone();
    s.samples.clear();
    format!("{s:?}")
}

#[test]
fn a_lean_run_gives_the_full_runs_summary_severity_and_frames_bit_for_bit() {
    for name in SCENES {
        let scene = common::scene(name, &[]);
        let mut full_frames = Frames::default();
        let full = run(&scene, false, &mut full_frames);
        assert!(full.severity.is_some(), "{name}");
        assert_eq!(full.sample_count, full.samples.len(), "{name}");
        // nobody reads the swing's samples
        let lean = run(&scene, true, &mut NoRecorder);
        assert_eq!(numbers(&lean), numbers(&full), "{name}");
        assert_eq!(lean.severity, full.severity, "{name}");
        // the samples it keeps (around the first contact) are the full run's
        let c = &full.contacts[0];
        let end = c.duration_s.map_or(full.duration_s, |d| c.onset_time_s + d);
        let d = end - c.onset_time_s;
        let window: Vec<_> = full
            .samples
            .iter()
            .filter(|s| s.t >= c.onset_time_s - d && s.t <= end + d)
            .copied()
            .collect();
        let kept: Vec<_> = lean
            .samples
            .iter()
            .filter(|s| s.t >= c.onset_time_s - d && s.t <= end + d)
            .copied()
            .collect();
        assert!(!window.is_empty() && kept == window, "{name}");
        // a recorder that reads every sample gets every frame as the full run hands it
        let mut every = Frames::default();
        let lean_every = run(&scene, true, &mut every);
        assert_eq!(numbers(&lean_every), numbers(&full), "{name}");
        assert_eq!(every.log, full_frames.log, "{name}");
        // a recorder that picks samples gets the same frames (but for its samples)
        let mut chosen = Frames {
            choice: Some(SwingSamples::Chosen),
            every: 200,
            ..Frames::default()
        };
        let lean_chosen = run(&scene, true, &mut chosen);
        assert_eq!(numbers(&lean_chosen), numbers(&full), "{name}");
        let mut full_blind = Frames {
            choice: Some(SwingSamples::Chosen),
            ..Frames::default()
        };
        run(&scene, false, &mut full_blind);
        assert_eq!(chosen.log, full_blind.log, "{name}");
    }
}

/// The severity of the contact stretches against flexrig-safety's over every sample (the
/// computation before the stretches): the peaks, times and energies identical, HIC within
/// 1e-12 of itself (round-off of a running integral started at t = 0 rather than at the
/// stretch), its window the same to 1e-12 s.
#[test]
fn the_contact_stretches_give_the_whole_traces_severity() {
    use flexrig_safety::{ContactAreaModel, ContactTraces, severity};
    for name in SCENES {
        let scene = common::scene(name, &[]);
        let full = run(&scene, false, &mut NoRecorder);
        let s = &full.samples;
        let col = |f: fn(&flexrig_rig::sensors::SensorSample) -> f64| -> Vec<f64> {
            s.iter().map(f).collect()
        };
        let (t, f, d, a) = (
            col(|x| x.t),
            col(|x| x.force_n),
            col(|x| x.indentation_m),
            col(|x| x.operator_accel_mps2.abs()),
        );
        let whole = severity(
            &ContactTraces {
                times: &t,
                force: &f,
                indentation: &d,
                head_acceleration: Some(&a),
            },
            &ContactAreaModel::dome_models(scene.file.robot.dome_radius_m),
        )
        .unwrap();
        let ours = of_samples(s, scene.file.robot.dome_radius_m).unwrap();
        assert_eq!(ours.peak_force_n, whole.peak_force_n, "{name}");
        assert_eq!(
            ours.time_of_peak_force_s, whole.time_of_peak_force_s,
            "{name}"
        );
        assert_eq!(ours.pressure, whole.pressure, "{name}");
        assert_eq!(
            ours.energy_transferred_j, whole.energy_transferred_j,
            "{name}"
        );
        assert_eq!(ours.contact_work_j, whole.contact_work_j, "{name}");
        assert_eq!(
            ours.peak_acceleration_mps2, whole.peak_acceleration_mps2,
            "{name}"
        );
        for (x, y) in [(&ours.hic15, &whole.hic15), (&ours.hic36, &whole.hic36)] {
            let (x, y) = (x.unwrap(), y.unwrap());
            assert!((x.hic / y.hic - 1.0).abs() <= 1e-12, "{name}: {x:?} {y:?}");
            assert!((x.t1_s - y.t1_s).abs() <= 1e-12, "{name}: {x:?} {y:?}");
            assert!((x.t2_s - y.t2_s).abs() <= 1e-12, "{name}: {x:?} {y:?}");
        }
    }
}

/// Where the swing's acceleration is not small against the contact's, the stretches do not
/// settle the peak acceleration: the severity falls back to every sample, and a lean run
/// computes them all — still the full run's numbers. (A soft, slow contact: the aluminium
/// block released from 2° onto the light load.)
#[test]
fn a_weak_contact_falls_back_to_every_sample_and_still_agrees() {
    let scene = common::scene(
        "cj_light_load",
        &[("release_angle_deg = 30.0", "release_angle_deg = 0.5")],
    );
    let full = run(&scene, false, &mut NoRecorder);
    let lean = run(&scene, true, &mut NoRecorder);
    assert_eq!(numbers(&lean), numbers(&full));
}
