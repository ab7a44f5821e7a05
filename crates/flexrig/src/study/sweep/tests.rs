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

/// The notes, the last cell, survive the CSV (commas and quotes inside) and a table written
/// before the column existed still reads, its notes empty.
#[test]
fn the_notes_cell_round_trips_and_an_older_table_reads_without_it() {
    let mut summary = vec![None; SUMMARY_COLUMNS.len()];
    summary[0] = Some(3520.79);
    let row = SweepRow {
        index: 0,
        values: vec!["2.0".into()],
        status: "ok".into(),
        error: String::new(),
        summary,
        notes: "the link arrived at 1.9 m/s, slower than \"commanded\"; a second".into(),
    };
    let header = csv_header(&["drive.command.profile.speed"]);
    assert!(header.ends_with(",notes"), "{header}");
    let text = format!("{header}\n{}\n", csv_line(&row));
    let back = read_rows(&text, 1).unwrap();
    assert_eq!(back[&0], row);
    // the same table without its notes column
    let old_header = header.trim_end_matches(",notes");
    let line = csv_line(&row);
    let old_line = &line[..line.rfind(",\"").expect("the quoted notes")];
    let back = read_rows(&format!("{old_header}\n{old_line}\n"), 1).unwrap();
    assert_eq!(back[&0].notes, "");
    assert_eq!(back[&0].summary, row.summary);
}
