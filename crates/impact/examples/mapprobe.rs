use flexrig_impact::eta::EtaSettings;
use flexrig_impact::map::*;
use std::time::Instant;
fn main() {
    for m_h in [4.0, 1000.0] {
        let spec = MapSpec { m_h, n: 2.0, mass_ratio: LogRange { from: 1e-3, to: 1e2, points: 30 }, stiffness_ratio: LogRange { from: 1e-7, to: 1.0, points: 30 } };
        let t = Instant::now();
        let st = EtaSettings { method: flexrig_impact::eta::ClMethod::Modal { mesh: flexrig_impact::graded::GradedMesh::DEFAULT, tol: 1e-5 }, ..EtaSettings::DEFAULT }; let pts = eta_map(&spec, &st).unwrap();
        let failed: Vec<_> = pts.iter().filter(|p| p.row.is_err()).collect();
        println!("m_h {m_h}: {:.2} s, {} failed", t.elapsed().as_secs_f64(), failed.len());
        for f in failed.iter().take(5) { println!("  {} {} {:?}", f.mass_ratio, f.stiffness_ratio, f.row); }
        let beats = pts.iter().filter(|p| p.row.as_ref().map(|r| r.eta_fe < 0.95).unwrap_or(false)).count();
        println!("  CL beats CJ by >5%: {beats} of {}", pts.len());
    }
}
