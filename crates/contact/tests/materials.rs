//! The bundled materials file carries the paper's fits (§III-B), and bad files are rejected with
//! the field path.

use flexrig_contact::{ContactError, Materials};

#[test]
fn bundled_materials_are_the_papers_fits() {
    let m = Materials::bundled().unwrap();
    assert_eq!(m.dome_radius_m(), 0.0715);
    // (name, k [N/m^n], n, block mass [kg]) as printed in the paper, §III-B.
    for (name, k, n, mass) in [
        ("abs", 1.311e7, 1.817, 0.039),
        ("skinned_aluminium", 7.359e7, 1.961, 0.398),
        ("skinned_iron", 9.642e7, 2.002, 4.008),
    ] {
        let mat = m.get(name).unwrap();
        assert_eq!(
            (mat.hertz.k(), mat.hertz.n(), mat.block_mass_kg),
            (k, n, mass)
        );
    }
    assert_eq!(m.all().len(), 3);
}

#[test]
fn unknown_material_lists_the_known_ones() {
    let m = Materials::bundled().unwrap();
    let e = m.get("steel").unwrap_err().to_string();
    assert!(e.contains("steel") && e.contains("skinned_iron"), "{e}");
}

#[test]
fn bad_files_name_the_field() {
    let bad_n = "[dome]\nradius_m = 0.07\n[material.x]\ndescription = \"\"\nk = 1e7\nn = -2\nblock_mass_kg = 1\n";
    let e = Materials::from_toml_str(bad_n).unwrap_err().to_string();
    assert!(e.contains("material.x.n") && e.contains("-2"), "{e}");
    let bad_mass = bad_n.replace("n = -2", "n = 2").replace("= 1\n", "= 0\n");
    let e = Materials::from_toml_str(&bad_mass).unwrap_err().to_string();
    assert!(e.contains("material.x.block_mass_kg"), "{e}");
    let unknown_key = bad_n.replace("n = -2", "n = 2\ncolour = 3");
    assert!(matches!(
        Materials::from_toml_str(&unknown_key),
        Err(ContactError::MaterialsSyntax(_))
    ));
    let no_materials = "[dome]\nradius_m = 0.07\n[material]\n";
    assert!(Materials::from_toml_str(no_materials).is_err());
    let bad_dome = bad_n.replace("0.07", "-0.07").replace("n = -2", "n = 2");
    let e = Materials::from_toml_str(&bad_dome).unwrap_err().to_string();
    assert!(e.contains("dome.radius_m"), "{e}");
}
