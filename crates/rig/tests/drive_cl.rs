//! A motor on the robot joint of the test bed (`[robot.drive]`), CL: the compliant link clamped
//! to the motor's hub.

mod common;

use flexrig_contact::Materials;
use flexrig_rig::{
    DriveFrame, Frame, RigError, RunOptions, RunSummary, Scene, Simulation, run::Recorder,
};

/// Keeps every frame's time, energy and drive channels.
#[derive(Default)]
struct Keep(Vec<(f64, f64, DriveFrame)>);

impl Recorder for Keep {
    fn frame(&mut self, frame: &Frame<'_>) -> Result<(), RigError> {
        if let Some(d) = frame.drive {
            self.0.push((frame.t, frame.energy, d));
        }
        Ok(())
    }
}

fn parse(text: &str) -> Result<Scene, RigError> {
    Scene::from_toml_str(text, &Materials::bundled().unwrap())
}

fn run_keep(scene: &Scene) -> (RunSummary, Vec<(f64, f64, DriveFrame)>) {
    let mut keep = Keep::default();
    let s = Simulation::new(scene, RunOptions::default())
        .unwrap()
        .run(&mut keep)
        .unwrap();
    (s, keep.0)
}

#[test]
fn smoke_the_bundled_driven_cl() {
    let scene = common::scene("rig_driven_cl", &[]);
    let t0 = std::time::Instant::now();
    let (s, frames) = run_keep(&scene);
    let d = s.drive.unwrap();
    eprintln!("{:?} s wall", t0.elapsed());
    eprintln!(
        "peak {} N at {} s, onset {}, v {} m/s, duration {:?}, steps {}, contact steps {}",
        s.peak_force_n,
        s.time_of_peak_s,
        s.onset_time_s,
        s.impact_velocity_mps,
        s.contact_duration_s,
        s.steps,
        s.contact_steps
    );
    eprintln!("{d:?}");
    let e0 = s.energy_initial_j;
    let mut worst: f64 = 0.0;
    for (_, e, f) in &frames {
        worst = worst.max((e - e0 - (f.motor_work_j - f.friction_dissipated_j)).abs());
    }
    eprintln!(
        "worst energy residual {worst:e} J of work {}",
        d.motor_work_j
    );
    for (t, _, f) in frames.iter().step_by(frames.len() / 20) {
        eprintln!("{t:.4} {f:?}");
    }
}
