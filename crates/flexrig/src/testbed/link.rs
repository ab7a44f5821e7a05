//! The link quantities a study needs beside a run's results: the link mass m_r, its bending
//! stiffness EI, the lateral tip stiffness k_δ, the joint's rotational stiffness k_θr and the
//! payload ratio m_e/m_r (paper §II, Eq. 1–3 and 5), computed from a scene: a test-bed scene
//! ([`of_scene`]) or a driven scene's link ([`of_driven`]). `flexrig run` prints and reports
//! them, the Python `RunResult` carries them and a sweep's table has a column of each
//! ([`COLUMNS`]).
//!
//! Both designs of the paper present the same lateral stiffness at the tip when the CJ's
//! torsion spring is k_θr = 3EI/L (Eq. 3):
//!
//! - CJ (rigid link on a torsion spring, Fig. 1a): k_θr is the joint's spring (the scene's
//!   `robot.torsion_spring_nm_per_rad`, 3EI/L when "matched"); k_δ = k_θr/L² (Eq. 1).
//! - CL (uniform compliant link on a revolute joint, Fig. 1b): k_δ = 3EI/L³ (Eq. 2); its
//!   k_θr is the equivalent joint stiffness 3EI/L (Eq. 3), the spring a CJ of the same lateral
//!   stiffness would have (the CL's own joint is rigid).
//!
//! EI is the bending stiffness of the link's beam in its compliant direction: E w t³/12 of the
//! test bed's flat beam (for a CJ, the beam its matched spring stands for: the CJ's link is
//! rigid in the strike plane), k_δ L³/3 of a driven scene's link (which gives k_δ).

use flexrig_impact::LinkParams;
use flexrig_lumped::prb::{
    equal_stiffness_torsion_spring, lateral_stiffness_cj, lateral_stiffness_cl,
};
use flexrig_rig::{Design, Override, Scene};
use serde::Serialize;

use crate::Error;

/// The link quantities of one design; the field names are the JSON keys and the sweep table's
/// columns ([`COLUMNS`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LinkQuantities {
    /// Link mass m_r \[kg\] (uniform link; the test bed's ρ w t L).
    pub m_r_kg: f64,
    /// Bending stiffness EI of the link in its compliant direction [N·m²].
    pub ei_n_m2: f64,
    /// Lateral tip stiffness k_δ [N/m]: k_θr/L² for the CJ (Eq. 1), 3EI/L³ for the CL (Eq. 2).
    pub k_delta_n_per_m: f64,
    /// Joint rotational stiffness k_θr [N·m/rad]: the CJ's torsion spring; for the CL the
    /// equivalent 3EI/L (Eq. 3).
    pub k_theta_r_nm_per_rad: f64,
    /// Payload over link mass m_e/m_r (the mass ratio of Eq. 5, m_eff = m_e + γ m_r/3).
    pub m_e_over_m_r: f64,
}

/// The sweep table's columns of [`LinkQuantities`], in [`LinkQuantities::values`]' order.
pub const COLUMNS: [&str; 5] = [
    "m_r_kg",
    "ei_n_m2",
    "k_delta_n_per_m",
    "k_theta_r_nm_per_rad",
    "m_e_over_m_r",
];

impl LinkQuantities {
    /// The values in [`COLUMNS`]' order.
    pub fn values(&self) -> [f64; 5] {
        [
            self.m_r_kg,
            self.ei_n_m2,
            self.k_delta_n_per_m,
            self.k_theta_r_nm_per_rad,
            self.m_e_over_m_r,
        ]
    }

    /// The quantities as JSON keys ([`COLUMNS`]) of `value`, an object (a run's summary).
    pub fn insert_into(&self, value: &mut serde_json::Value) {
        if let Some(map) = value.as_object_mut() {
            for (name, v) in COLUMNS.iter().zip(self.values()) {
                map.insert((*name).into(), serde_json::json!(v));
            }
        }
    }
}

/// The link quantities of a test-bed scene (as loaded and validated, overrides applied): m_r =
/// ρ w t L, EI = E w t³/12 (the scene's own), L the scene's link length (axis to payload), m_e
/// its payload; k_δ and k_θr by design (module documentation, Eq. 1–3).
pub fn of_scene(scene: &Scene) -> LinkQuantities {
    let robot = &scene.file.robot;
    let (m_r, ei, length) = (scene.link_mass_kg, scene.link_ei, robot.length_m);
    let (k_delta, k_theta_r) = match robot.design {
        Design::Cj => (
            lateral_stiffness_cj(scene.torsion_spring, length),
            scene.torsion_spring,
        ),
        Design::Cl => (
            lateral_stiffness_cl(ei, length),
            equal_stiffness_torsion_spring(ei, length),
        ),
    };
    LinkQuantities {
        m_r_kg: m_r,
        ei_n_m2: ei,
        k_delta_n_per_m: k_delta,
        k_theta_r_nm_per_rad: k_theta_r,
        m_e_over_m_r: robot.payload_kg / m_r,
    }
}

/// The link quantities of a driven scene's link (`[link]`: m_r, L, k_δ, m_e), the same for its
/// CJ and CL: EI = k_δ L³/3 (Eq. 2), k_θr = k_δ L² (Eq. 1 and 3).
pub fn of_driven(link: &LinkParams) -> LinkQuantities {
    LinkQuantities {
        m_r_kg: link.m_r,
        ei_n_m2: link.ei(),
        k_delta_n_per_m: link.k_delta,
        k_theta_r_nm_per_rad: link.k_theta(),
        m_e_over_m_r: link.m_e / link.m_r,
    }
}

/// The link quantities of a scene's TOML `text` with `overrides` (a test-bed or a driven scene),
/// validated as a run validates it (errors name the field).
pub fn of_text(text: &str, overrides: &[Override]) -> Result<LinkQuantities, Error> {
    if crate::driven::scene::is_driven_text(text) {
        let scene = crate::driven::scene::DrivenScene::with_overrides(text, overrides)?;
        return Ok(of_driven(&scene.strike.link));
    }
    let materials = flexrig_contact::Materials::bundled()?;
    Ok(of_scene(&flexrig_rig::scene_with_overrides(
        text, overrides, &materials,
    )?))
}

#[cfg(test)]
mod tests {
    use super::*;

    const CL: &str = include_str!("../../../../assets/scenes/cl_aluminium.toml");
    const CJ: &str = include_str!("../../../../assets/scenes/cj_aluminium.toml");
    const DRIVEN_CL: &str = include_str!("../../../../assets/scenes/driven_cl_free_head.toml");

    fn close(got: f64, want: f64, rel: f64, what: &str) {
        assert!(
            (got - want).abs() <= rel * want.abs(),
            "{what}: {got:e} vs {want:e}"
        );
    }

    #[test]
    fn the_bundled_cl_and_cj_links_by_hand() {
        // assets/scenes/cl_aluminium.toml, by hand: E = 1.5e9 Pa, ρ = 905 kg/m³,
        // w = 0.064559 m, t = 0.0025824 m, L = 0.33802 m, m_e = 0.412 kg
        let (e, rho, w, t, l, m_e) = (1.5e9, 905.0, 0.064559, 0.0025824, 0.33802, 0.412);
        let m_r = rho * w * t * l; // 0.05100 kg ("m_r = 51 g" in the scene's description)
        let ei = e * w * t * t * t / 12.0; // 1.39e-1 N·m²
        let cl = of_text(CL, &[]).unwrap();
        close(cl.m_r_kg, m_r, 1e-15, "m_r");
        close(cl.m_r_kg, 0.051, 2e-3, "m_r against the description's 51 g");
        close(cl.ei_n_m2, ei, 1e-15, "EI");
        close(
            cl.k_delta_n_per_m,
            3.0 * ei / (l * l * l),
            1e-15,
            "k_δ (Eq. 2)",
        );
        close(cl.k_theta_r_nm_per_rad, 3.0 * ei / l, 1e-15, "k_θr (Eq. 3)");
        // the CJ scene's spring 1.2334 N·m/rad was chosen as 3EI/L of this link (Eq. 3)
        close(
            cl.k_theta_r_nm_per_rad,
            1.2334,
            1e-4,
            "3EI/L against 1.2334",
        );
        close(cl.m_e_over_m_r, m_e / m_r, 1e-15, "m_e/m_r");
        // the CJ: the scene's spring, k_δ = k_θr/L² (Eq. 1), the same beam
        let cj = of_text(CJ, &[]).unwrap();
        close(cj.k_theta_r_nm_per_rad, 1.2334, 1e-15, "CJ k_θr");
        close(
            cj.k_delta_n_per_m,
            1.2334 / (l * l),
            1e-15,
            "CJ k_δ (Eq. 1)",
        );
        close(
            cj.k_delta_n_per_m,
            cl.k_delta_n_per_m,
            1e-4,
            "equal lateral stiffness",
        );
        assert_eq!((cj.m_r_kg, cj.ei_n_m2), (cl.m_r_kg, cl.ei_n_m2));
    }

    #[test]
    fn overrides_and_the_matched_spring_follow_the_link() {
        let set = |p: &str, v: &str| Override::parse(&format!("{p}={v}")).unwrap();
        // a thicker CJ link with the matched spring: k_θr = 3EI/L of the new link
        let cj = of_text(
            CJ,
            &[
                set("robot.thickness_m", "0.004"),
                set("robot.torsion_spring_nm_per_rad", "\"matched\""),
                set("robot.payload_kg", "0.2"),
            ],
        )
        .unwrap();
        let (w, t, l) = (0.064559, 0.004, 0.33802);
        let ei = 1.5e9 * w * t * t * t / 12.0;
        close(cj.ei_n_m2, ei, 1e-15, "EI");
        close(cj.k_theta_r_nm_per_rad, 3.0 * ei / l, 1e-15, "matched k_θr");
        close(cj.m_e_over_m_r, 0.2 / (905.0 * w * t * l), 1e-15, "m_e/m_r");
        let e = of_text(CJ, &[set("robot.length_m", "-1")]).unwrap_err();
        assert!(e.to_string().contains("robot.length_m"), "{e}");
    }

    #[test]
    fn the_driven_link_from_its_lateral_stiffness() {
        // driven_cl_free_head.toml: m_r = 10 kg, L = 1 m, k_δ = 1e8 N/m, m_e = 0.1 kg
        let q = of_text(DRIVEN_CL, &[]).unwrap();
        assert_eq!(q.m_r_kg, 10.0);
        assert_eq!(q.k_delta_n_per_m, 1e8);
        close(q.ei_n_m2, 1e8 / 3.0, 1e-15, "EI = k_δ L³/3");
        close(q.k_theta_r_nm_per_rad, 1e8, 1e-15, "k_θr = k_δ L²");
        close(q.m_e_over_m_r, 0.01, 1e-15, "m_e/m_r");
    }
}
