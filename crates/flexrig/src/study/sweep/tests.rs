use super::*;

#[test]
fn the_table_carries_the_severity_columns_with_their_units() {
    let header = csv_header(&["robot.payload_kg"]);
    for column in crate::shared::severity::SEVERITY_COLUMNS {
        assert!(header.split(',').any(|c| c == column), "{column}");
    }
    let n = crate::shared::severity::SEVERITY_COLUMNS.len();
    assert_eq!(
        SUMMARY_COLUMNS[SEVERITY_START..SEVERITY_START + n],
        crate::shared::severity::SEVERITY_COLUMNS
    );
    // the link quantities, one block
    let at = link_offset();
    assert_eq!(SUMMARY_COLUMNS[at..at + 5], crate::testbed::link::COLUMNS);
    assert_eq!(SUMMARY_COLUMNS[DRIVEN_START..], DRIVEN_COLUMNS);
    // every column but the counts, HIC and the mass ratio (no unit) names its unit
    for column in SUMMARY_COLUMNS {
        let unitless = [
            "contacts",
            "steps",
            "contact_steps",
            "hic15",
            "hic36",
            "m_e_over_m_r",
        ];
        let units = [
            "_n",
            "_s",
            "_mps",
            "_m",
            "_n_s",
            "_j",
            "_pa",
            "_mps2",
            "_g",
            "_kg",
            "_n_m2",
            "_n_per_m",
            "_nm_per_rad",
            "_nm",
            "_rad_s",
        ];
        assert!(
            unitless.contains(&column) || units.iter().any(|u| column.ends_with(u)),
            "{column}"
        );
    }
}
