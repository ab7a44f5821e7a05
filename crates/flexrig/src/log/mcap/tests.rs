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

/// Every message of a log (topic, times, sequence, bytes) of `scene`, sampled lean or in
/// full, at `rates`, with the summary and severity records: (messages, summary).
fn logged(scene: &Scene, lean: bool, rates: LogRates) -> (Vec<String>, RunSummary) {
    let mut log = McapRecorder::new(Cursor::new(Vec::new()), scene, "")
        .unwrap()
        .with_rates(rates);
    let sim = Simulation::new(scene, RunOptions::default()).unwrap();
    let sim = if lean { sim.with_lean_samples() } else { sim };
    let summary = sim.run(&mut log).unwrap();
    log.write_summary(&summary).unwrap();
    log.write_severity(&summary).unwrap();
    let bytes = log.finish_into_inner().unwrap().into_inner();
    let messages = mcap::MessageStream::new(&bytes)
        .unwrap()
        .map(|m| {
            let m = m.unwrap();
            format!(
                "{} {} {} {} {:?}",
                m.channel.topic, m.sequence, m.log_time, m.publish_time, m.data
            )
        })
        .collect();
    (messages, summary)
}

/// A lean run's log (the swing's samples computed only where the decimation writes them)
/// holds the full run's messages bit for bit, summary and severity included, on every
/// bundled test-bed scene; also when every step is logged.
#[test]
fn a_lean_runs_log_is_the_full_runs_bit_for_bit() {
    for name in [
        "cj_aluminium",
        "cj_iron",
        "cj_light_load",
        "cl_aluminium",
        "cl_iron",
        "cl_light_load",
        "rig_driven_cj",
        "rig_driven_cl",
    ] {
        let scene = crate::testbed::scenes::bundled_scene(name, &[]).unwrap();
        for rates in [LogRates::DECIMATED, LogRates::EVERY_STEP] {
            let (full, full_summary) = logged(&scene, false, rates);
            let (lean, lean_summary) = logged(&scene, true, rates);
            assert_eq!(full.len(), lean.len(), "{name}");
            for (a, b) in full.iter().zip(&lean) {
                assert_eq!(a, b, "{name}");
            }
            assert_eq!(
                serde_json::to_string(&full_summary).unwrap(),
                serde_json::to_string(&lean_summary).unwrap(),
                "{name}"
            );
            assert_eq!(full_summary.sample_count, lean_summary.sample_count);
            // the layout beside the log scales its plots by the samples around the contact
            let w = crate::log::layout::contact_window(&full_summary).unwrap();
            assert_eq!(
                format!("{:?}", crate::log::layout::plot_axes(&full_summary, w)),
                format!("{:?}", crate::log::layout::plot_axes(&lean_summary, w)),
                "{name}"
            );
        }
    }
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
