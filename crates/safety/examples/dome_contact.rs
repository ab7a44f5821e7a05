//! Prints the contact-area models for the paper's dome (R = 71.5 mm) on skinned aluminium
//! (k = 7.359e7 N/m^n, n = 1.961), and the permissible speed of the test bed's CJ and CL links
//! against the hand by the standard's formula and by the energy method (the numbers quoted in
//! docs/safety.md). Run: `cargo run --release -p flexrig-safety --example dome_contact`.

use flexrig_contact::Hertz;
use flexrig_lumped::prb::{PrbLink, lateral_stiffness_cj};
use flexrig_safety::{
    BodyModel, ContactAreaModel, ContactKind, EnergyContact, LinkStiffness, SafetyError,
    StandardContact,
};

fn main() -> Result<(), SafetyError> {
    let (k, n, r) = (7.359e7, 1.961, 0.0715);
    let skin = Hertz::new(k, n)?;
    let hertz = ContactAreaModel::HertzSphere { radius_m: r };
    let thin = ContactAreaModel::ThinLayer { radius_m: r };
    println!(
        "| force [N] | δ_c [mm] | A Hertz [cm²] | p̄ Hertz [N/cm²] | p₀ Hertz | A thin layer [cm²] | p̄ thin | p₀ thin |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for f in [65.0, 140.0, 280.0, 300.0, 420.0] {
        let d = skin.indentation(f);
        let (ah, at) = (hertz.area(d), thin.area(d));
        let (ph, pt) = (f / ah / 1e4, f / at / 1e4);
        println!(
            "| {f:.0} | {:.3} | {:.3} | {:.1} | {:.1} | {:.3} | {:.1} | {:.1} |",
            d * 1e3,
            ah * 1e4,
            ph,
            1.5 * ph,
            at * 1e4,
            pt,
            2.0 * pt
        );
    }

    let model = BodyModel::iso_ts_15066_2016()?;
    let hand = model.region("hands_and_fingers")?;
    let area = hand.most_sensitive_area();
    let limits = hand.limits(Some(area), ContactKind::Transient)?;
    println!(
        "\nhand, transient, {}: F = {} N, p = {} N/cm²",
        area.name(),
        limits.force,
        limits.pressure.unwrap() / 1e4
    );
    // Test bed (§VI): m_r = 51 g, payload 412 g, k_θr = 1.2334 N·m/rad, L = 0.34 m (scene files).
    let k_delta = lateral_stiffness_cj(1.2334, 0.34);
    println!("test-bed link lateral stiffness k_δ = k_θr/L² = {k_delta:.3} N/m");
    println!(
        "| link | m_eff [kg] | standard v_max [m/s] | energy: rigid, Hertz area | energy: rigid, thin layer | energy: k_δ = 1e4 N/m | energy: k_δ = 200 N/m | energy: test-bed k_δ |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for (name, gamma) in [("CJ (γ = 1)", 1.0), ("CL (γ = 2/3)", 2.0 / 3.0)] {
        let m_eff = PrbLink::new(gamma, 0.051, 0.412)?.effective_mass();
        let standard = StandardContact {
            region: hand,
            area: None,
            robot_mass: m_eff,
            kind: ContactKind::Transient,
        }
        .permissible_speed()?;
        let energy = |link, area| -> Result<String, SafetyError> {
            let c = EnergyContact::for_region(
                hand,
                ContactKind::Transient,
                m_eff,
                skin,
                link,
                Some(area),
            )?;
            let v = c.permissible_speed(limits)?;
            Ok(format!("{:.3} ({:?})", v.v_max, v.governing))
        };
        println!(
            "| {name} | {m_eff:.4} | {:.3} | {} | {} | {} | {} | {} |",
            standard.v_max,
            energy(LinkStiffness::Rigid, hertz)?,
            energy(LinkStiffness::Rigid, thin)?,
            energy(LinkStiffness::Finite(1e4), thin)?,
            energy(LinkStiffness::Finite(200.0), thin)?,
            energy(LinkStiffness::Finite(k_delta), thin)?,
        );
    }
    Ok(())
}
