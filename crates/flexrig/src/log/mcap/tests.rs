use std::io::Cursor;

use flexrig_rig::{NoRecorder, RunOptions, Simulation};

use super::*;

/// The `/scene` message times \[s\] of an MCAP file in memory.
fn scene_times(bytes: &[u8]) -> Vec<f64> {
    mcap::MessageStream::new(bytes)
        .unwrap()
        .map(|m| m.unwrap())
        .filter(|m| m.channel.topic == "/scene")
        .map(|m| m.log_time as f64 * 1e-9)
        .collect()
}

#[test]
fn the_free_swing_is_drawn_at_the_scene_rate_without_changing_the_run() {
    for name in ["cj_iron", "cl_aluminium"] {
        let scene = crate::testbed::scenes::bundled_scene(name, &[]).unwrap();
        let plain = Simulation::new(&scene, RunOptions::default())
            .unwrap()
            .run(&mut NoRecorder)
            .unwrap();
        let mut log = McapRecorder::new(Cursor::new(Vec::new()), &scene, "").unwrap();
        let logged = Simulation::new(&scene, RunOptions::default())
            .unwrap()
            .run(&mut log)
            .unwrap();
        // the same run, bit for bit (the poses come from the dense output)
        assert_eq!(
            serde_json::to_string(&plain).unwrap(),
            serde_json::to_string(&logged).unwrap(),
            "{name}"
        );
        let bytes = log.finish_into_inner().unwrap().into_inner();
        let onset = plain.contacts[0].onset_time_s;
        let swing: Vec<f64> = scene_times(&bytes)
            .into_iter()
            .filter(|t| *t < onset)
            .collect();
        // 60 frames a second over the swing: the end of the first integrator step, then
        // every multiple of the period (without them, one frame per step: about a dozen)
        let period = 1.0 / 60.0;
        let expected = (onset / period).floor();
        assert!(
            (swing.len() as f64 - expected).abs() <= 2.0,
            "{name}: {} frames over a {onset} s swing",
            swing.len()
        );
        assert!(swing[1] - swing[0] < 2.0 * period, "{name}: {swing:?}");
        for pair in swing[1..].windows(2) {
            let gap = pair[1] - pair[0];
            assert!(
                (gap - period).abs() < 1e-6,
                "{name}: frames {pair:?} {gap} s apart"
            );
        }
    }
}
