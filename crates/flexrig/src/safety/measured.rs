//! A measured impact, judged (`flexrig safety --trace FILE`, Python
//! `flexrig.safety(region, trace=…)`): a force trace measured on the real robot (a
//! pressure/force measuring device per ISO/PAS 5672, a force sensor), with the struck body's
//! acceleration and the indentation when they were measured, read from a CSV file; its severity
//! by the one severity function every run uses ([`flexrig_safety::severity`]) and its verdict
//! against the body region's limits of ISO/TS 15066:2016 Table A.2 — so a simulation and a
//! measurement are held against the same limits by the same code.
//!
//! Also the contact area as the user writes it ([`parse_area`]: `1cm2`, `1e-4m2`, `100mm2`;
//! a bare number is refused, its unit being ambiguous) and the warnings about implausible
//! contact geometries ([`area_warnings`]), which `flexrig safety` shares.
//!
//! **The CSV** (docs/safety.md, "A measured impact"): a header, then one sample per line,
//! comma-separated; blank lines and lines starting with `#` are skipped, a byte-order mark is
//! ignored. Each column is named with its unit: `t [s]`, `F [N]`, `a [m/s^2]`, `delta [mm]` (the
//! unit in square brackets or parentheses), or flexrig's own `t_s`, `force_n`,
//! `head_acceleration_mps2`, `indentation_m` (the unit after the last underscore) — so the
//! trace `flexrig strike --trace-every` writes is read as it is. Time and force are required,
//! acceleration and indentation optional; a column of another name is ignored (and listed); a
//! known name without a unit, or with a unit it does not take, is refused.

use std::path::{Path, PathBuf};

use flexrig_safety::{
    BodyModel, ContactAreaModel, ContactKind, ContactTraces, HicSeverity, PressureSeverity,
    STANDARD_GRAVITY, Severity, spring_energy_at_force,
};
use serde::{Deserialize, Serialize};

pub use flexrig_rig::plausibility::Warning;

use crate::Error;
use crate::shared::output::display_number;

/// One square centimetre in m² (the unit of the standard's pressures, N/cm², Table A.2).
pub const SQUARE_CENTIMETRE_M2: f64 = 1e-4;

/// Largest plausible contact area \[m²\]: 100 cm², a 10 cm × 10 cm flat face, larger than a
/// palm; beyond it the number looks like a unit slip (m² for cm²).
pub const LARGEST_PLAUSIBLE_AREA_M2: f64 = 100.0 * SQUARE_CENTIMETRE_M2;

/// Smallest plausible contact area \[m²\]: 0.01 cm² (1 mm², a needle's tip); below it the
/// number looks like a unit slip (cm² written as m² twice over).
pub const SMALLEST_PLAUSIBLE_AREA_M2: f64 = 0.01 * SQUARE_CENTIMETRE_M2;

/// Largest plausible dome radius \[m\] of the Hertz-sphere and thin-layer area models: 0.5 m;
/// beyond it the radius looks like millimetres (the paper's dome is 71.5 mm).
pub const LARGEST_PLAUSIBLE_RADIUS_M: f64 = 0.5;

/// The area of `text` \[m²\]: a positive number with its unit, `cm2` (also `cm²`, `cm^2`),
/// `m2` or `mm2`, e.g. `1cm2`, `1e-4m2`, `100 mm2`. A bare number is refused: the standard
/// and its users work in cm², flexrig in SI units, and a silent guess would be off by 10⁴.
/// Errors name `flag`.
pub fn parse_area(flag: &str, text: &str) -> Result<f64, Error> {
    let bad = |why: &str| Error::InvalidArgument {
        arg: flag.into(),
        value: text.into(),
        allowed: format!(
            "{why}: give the area with its unit, e.g. 1cm2 (square centimetres, the unit of \
             the standard's pressures), 1e-4m2 or 100mm2"
        ),
    };
    let compact: String = text.chars().filter(|c| !c.is_whitespace()).collect();
    let lower = compact.to_lowercase();
    let units: [(&str, f64); 9] = [
        ("cm2", SQUARE_CENTIMETRE_M2),
        ("cm²", SQUARE_CENTIMETRE_M2),
        ("cm^2", SQUARE_CENTIMETRE_M2),
        ("mm2", 1e-6),
        ("mm²", 1e-6),
        ("mm^2", 1e-6),
        ("m2", 1.0),
        ("m²", 1.0),
        ("m^2", 1.0),
    ];
    let Some((number, scale)) = units
        .iter()
        .find_map(|(unit, scale)| lower.strip_suffix(unit).map(|n| (n, *scale)))
    else {
        return Err(if lower.parse::<f64>().is_ok() {
            bad("a bare number has no unit")
        } else {
            bad("not an area")
        });
    };
    match number.parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 && v * scale <= 1e6 => Ok(v * scale),
        Ok(_) => Err(bad("must be a finite area in (0, 1e6 m²]")),
        Err(_) => Err(bad("not a number before the unit")),
    }
}

/// The warnings about a contact geometry that is valid but looks like a mistake: a fixed area
/// above [`LARGEST_PLAUSIBLE_AREA_M2`] or below [`SMALLEST_PLAUSIBLE_AREA_M2`] (named
/// `area_flag`), a dome radius above [`LARGEST_PLAUSIBLE_RADIUS_M`] (named `radius_flag`).
pub fn area_warnings(
    model: Option<&ContactAreaModel>,
    area_flag: &str,
    radius_flag: &str,
) -> Vec<Warning> {
    let cm2 = |a: f64| display_number(a / SQUARE_CENTIMETRE_M2);
    match model {
        Some(ContactAreaModel::Fixed { area_m2 }) if *area_m2 > LARGEST_PLAUSIBLE_AREA_M2 => {
            vec![Warning {
                field: area_flag.into(),
                message: format!(
                    "{} cm² is larger than the {} cm² of a 10 cm × 10 cm flat face: the \
                     pressure f/A is then small and may pass a contact that is not; check the \
                     unit (1cm2 is 1e-4m2)",
                    cm2(*area_m2),
                    cm2(LARGEST_PLAUSIBLE_AREA_M2)
                ),
            }]
        }
        Some(ContactAreaModel::Fixed { area_m2 }) if *area_m2 < SMALLEST_PLAUSIBLE_AREA_M2 => {
            vec![Warning {
                field: area_flag.into(),
                message: format!(
                    "{} cm² is smaller than the {} cm² (1 mm²) of a needle's tip: check the \
                     unit (1cm2 is 1e-4m2)",
                    cm2(*area_m2),
                    cm2(SMALLEST_PLAUSIBLE_AREA_M2)
                ),
            }]
        }
        Some(
            ContactAreaModel::HertzSphere { radius_m } | ContactAreaModel::ThinLayer { radius_m },
        ) if *radius_m > LARGEST_PLAUSIBLE_RADIUS_M => vec![Warning {
            field: radius_flag.into(),
            message: format!(
                "a dome radius of {} m looks like millimetres (the paper's dome is 0.0715 m); \
                 the radius is in metres",
                display_number(*radius_m)
            ),
        }],
        _ => Vec::new(),
    }
}

/// What a column of a trace holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Quantity {
    /// Time \[s\].
    Time,
    /// Contact force \[N\].
    Force,
    /// The struck body's acceleration [m/s²].
    Acceleration,
    /// Indentation of the body's surface \[m\].
    Indentation,
}

impl Quantity {
    fn words(self) -> &'static str {
        match self {
            Quantity::Time => "time",
            Quantity::Force => "force",
            Quantity::Acceleration => "acceleration",
            Quantity::Indentation => "indentation",
        }
    }

    /// The names a header may give it (lower case, spaces as underscores).
    fn of_name(name: &str) -> Option<Quantity> {
        match name {
            "t" | "time" => Some(Quantity::Time),
            "f" | "force" | "contact_force" => Some(Quantity::Force),
            "a" | "acc" | "accel" | "acceleration" | "head_acceleration" => {
                Some(Quantity::Acceleration)
            }
            "delta" | "δ" | "indentation" | "compression" => Some(Quantity::Indentation),
            _ => None,
        }
    }

    /// The units it takes (lower case) and their factor to SI.
    fn units(self) -> &'static [(&'static str, f64)] {
        match self {
            Quantity::Time => &[("s", 1.0), ("ms", 1e-3), ("us", 1e-6), ("µs", 1e-6)],
            Quantity::Force => &[("n", 1.0), ("kn", 1e3)],
            Quantity::Acceleration => &[
                ("m/s^2", 1.0),
                ("m/s²", 1.0),
                ("m/s2", 1.0),
                ("mps2", 1.0),
                ("g", STANDARD_GRAVITY),
            ],
            Quantity::Indentation => &[("m", 1.0), ("mm", 1e-3), ("um", 1e-6), ("µm", 1e-6)],
        }
    }

    fn unit_list(self) -> String {
        self.units()
            .iter()
            .map(|(u, _)| match *u {
                "n" => "N",
                "kn" => "kN",
                u => u,
            })
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// A column of the trace as its header gave it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TraceColumn {
    /// The header's text of the column.
    pub header: String,
    /// What it holds.
    pub quantity: Quantity,
    /// Its unit, as written.
    pub unit: String,
}

/// A trace read from a CSV file, in SI units.
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredTrace {
    /// Times \[s\], strictly increasing.
    pub times_s: Vec<f64>,
    /// Contact force \[N\].
    pub force_n: Vec<f64>,
    /// The struck body's acceleration [m/s²], when measured.
    pub acceleration_mps2: Option<Vec<f64>>,
    /// Indentation \[m\], when measured.
    pub indentation_m: Option<Vec<f64>>,
    /// The columns read.
    pub columns: Vec<TraceColumn>,
    /// The header's other columns, ignored.
    pub ignored_columns: Vec<String>,
}

/// The column of one header field: `Some(Ok)` a known quantity with its unit and factor,
/// `Some(Err)` a known name with a missing or wrong unit, `None` another column.
fn header_column(field: &str) -> Option<Result<(TraceColumn, f64), String>> {
    let normalise = |s: &str| s.trim().to_lowercase().replace([' ', '-'], "_");
    let bracketed = ['[', '(']
        .iter()
        .zip([']', ')'])
        .find_map(|(&open, close)| {
            let (name, rest) = field.split_once(open)?;
            let unit = rest.trim_end().strip_suffix(close)?;
            Some((normalise(name), unit.trim().to_string()))
        });
    let (quantity, unit) = match bracketed {
        Some((name, unit)) => (Quantity::of_name(&name)?, unit),
        None => {
            let whole = normalise(field);
            if let Some(q) = Quantity::of_name(&whole) {
                return Some(Err(format!(
                    "column {field:?} ({}) has no unit: write it with its unit, e.g. \
                     \"{field} [{}]\" (units: {})",
                    q.words(),
                    q.unit_list().split(", ").next().unwrap_or(""),
                    q.unit_list()
                )));
            }
            // flexrig's own form: name_unit
            let (name, unit) = whole.rsplit_once('_')?;
            (Quantity::of_name(name)?, unit.to_string())
        }
    };
    let factor = quantity
        .units()
        .iter()
        .find(|(u, _)| *u == unit.to_lowercase().replace(' ', ""))
        .map(|(_, f)| *f);
    Some(match factor {
        Some(f) => Ok((
            TraceColumn {
                header: field.trim().to_string(),
                quantity,
                unit,
            },
            f,
        )),
        None => Err(format!(
            "column {:?} ({}) has the unit {unit:?}; the units it takes: {}",
            field.trim(),
            quantity.words(),
            quantity.unit_list()
        )),
    })
}

/// Parses the CSV `text` of a measured trace (the module's format); an error names the line
/// (1-based), what is wrong on it and what is expected.
pub fn parse_trace_csv(text: &str) -> Result<MeasuredTrace, String> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut header: Option<Vec<Option<(usize, f64)>>> = None;
    let mut columns = Vec::new();
    let mut ignored = Vec::new();
    let mut values: [Vec<f64>; 4] = Default::default();
    let mut lines = Vec::new();
    for (index, raw) in text.lines().enumerate() {
        let line_no = index + 1;
        let line = raw.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        let at = |reason: String| format!("line {line_no}: {reason} (found {line:?})");
        let Some(slots) = &header else {
            let mut slots = Vec::with_capacity(fields.len());
            for field in &fields {
                match header_column(field) {
                    Some(Ok((column, factor))) => {
                        let q = column.quantity as usize;
                        if let Some(other) = columns
                            .iter()
                            .find(|c: &&TraceColumn| c.quantity == column.quantity)
                        {
                            return Err(at(format!(
                                "the header has two {} columns, {:?} and {:?}: keep one",
                                column.quantity.words(),
                                other.header,
                                column.header
                            )));
                        }
                        columns.push(column);
                        slots.push(Some((q, factor)));
                    }
                    Some(Err(reason)) => return Err(at(reason)),
                    None => {
                        if fields.iter().all(|f| f.parse::<f64>().is_ok()) {
                            return Err(at(
                                "the first line must be the header naming each column with its \
                                 unit, e.g. \"t [s], F [N], a [m/s^2], delta [mm]\""
                                    .into(),
                            ));
                        }
                        ignored.push(field.to_string());
                        slots.push(None);
                    }
                }
            }
            for required in [Quantity::Time, Quantity::Force] {
                if !columns.iter().any(|c| c.quantity == required) {
                    let found: Vec<String> = fields.iter().map(|f| format!("{f:?}")).collect();
                    return Err(at(format!(
                        "the header has no {} column (found {}); name it e.g. {}",
                        required.words(),
                        found.join(", "),
                        match required {
                            Quantity::Time => "\"t [s]\"",
                            _ => "\"F [N]\"",
                        }
                    )));
                }
            }
            header = Some(slots);
            continue;
        };
        if fields.len() != slots.len() {
            return Err(at(format!(
                "{} fields, the header has {} columns",
                fields.len(),
                slots.len()
            )));
        }
        for (field, slot) in fields.iter().zip(slots) {
            let Some((q, factor)) = slot else { continue };
            let name = &columns
                .iter()
                .find(|c| c.quantity as usize == *q)
                .map_or("", |c| c.header.as_str());
            match field.parse::<f64>() {
                Ok(v) if v.is_finite() => values[*q].push(v * factor),
                _ => {
                    return Err(at(format!("{name} = {field:?} is not a finite number")));
                }
            }
        }
        lines.push(line_no);
    }
    if header.is_none() {
        return Err(
            "the file has no header and no samples: expected a header such as \
                    \"t [s], F [N]\" and one sample per line"
                .into(),
        );
    }
    let [times, force, acceleration, indentation] = values;
    if times.len() < 2 {
        return Err(format!(
            "{} sample{} after the header: at least two are needed",
            times.len(),
            if times.len() == 1 { "" } else { "s" }
        ));
    }
    if let Some(i) = times.windows(2).position(|w| !(w[1] > w[0])) {
        return Err(format!(
            "line {}: time {} s is not after line {}'s {} s: times must increase strictly",
            lines[i + 1],
            display_number(times[i + 1]),
            lines[i],
            display_number(times[i])
        ));
    }
    let has = |q: Quantity| columns.iter().any(|c: &TraceColumn| c.quantity == q);
    Ok(MeasuredTrace {
        acceleration_mps2: has(Quantity::Acceleration).then_some(acceleration),
        indentation_m: has(Quantity::Indentation).then_some(indentation),
        times_s: times,
        force_n: force,
        columns,
        ignored_columns: ignored,
    })
}

/// Reads the trace of `path` ([`parse_trace_csv`]); an error names `flag`, the file and the
/// line.
pub fn read_trace(flag: &str, path: &Path) -> Result<MeasuredTrace, Error> {
    let text = crate::shared::output::read_text(path)?;
    parse_trace_csv(&text).map_err(|reason| Error::InvalidArgument {
        arg: flag.into(),
        value: path.display().to_string(),
        allowed: reason,
    })
}

/// How the transferred energy was computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum EnergyBasis {
    /// The work of the measured force over the measured indentation up to its largest value,
    /// ∫₀^{δ_max} f dδ (the severity's `energy_transferred_j`).
    ForceAndIndentation,
    /// Without an indentation: the energy the body region's spring of the standard stores at
    /// the peak force, F²/(2K) (ISO/TS 15066:2016 Eq. A.1 with Table A.3's K).
    BodySpringAtPeakForce,
}

/// The severity of a measured trace: [`Severity`]'s measures, the energy with its basis.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MeasuredSeverity {
    /// Peak contact force \[N\] (largest sample).
    pub peak_force_n: f64,
    /// Time of the peak force \[s\].
    pub time_of_peak_force_s: f64,
    /// Peak contact pressure under each contact-area model (empty: no area model).
    pub pressure: Vec<PressureSeverity>,
    /// The energy transferred to the body \[J\] ([`MeasuredSeverity::energy_transferred_from`]
    /// says how).
    pub energy_transferred_j: f64,
    /// How the transferred energy was computed.
    pub energy_transferred_from: EnergyBasis,
    /// Net work of the force over the indentation, ∮ f dδ \[J\] (with an indentation only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contact_work_j: Option<f64>,
    /// Largest |acceleration| of the struck body [m/s²] (with an acceleration only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub peak_acceleration_mps2: Option<f64>,
    /// The same in g₀ = 9.80665 m/s².
    #[serde(skip_serializing_if = "Option::is_none")]
    pub peak_acceleration_g: Option<f64>,
    /// HIC15 (window ≤ 15 ms) of |acceleration|.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hic15: Option<HicSeverity>,
    /// HIC36 (window ≤ 36 ms) of |acceleration|.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hic36: Option<HicSeverity>,
}

impl MeasuredSeverity {
    /// The measures every run reports ([`Severity`]), with an indentation (`None` without: its
    /// energy and contact work are then not the run summary's).
    pub fn as_run_severity(&self) -> Option<Severity> {
        Some(Severity {
            peak_force_n: self.peak_force_n,
            time_of_peak_force_s: self.time_of_peak_force_s,
            pressure: self.pressure.clone(),
            energy_transferred_j: self.energy_transferred_j,
            contact_work_j: self.contact_work_j?,
            peak_acceleration_mps2: self.peak_acceleration_mps2,
            peak_acceleration_g: self.peak_acceleration_g,
            hic15: self.hic15,
            hic36: self.hic36,
        })
    }
}

/// The severity of `trace` by [`flexrig_safety::severity`], the function every run uses: the
/// force below 0 counts as 0 (the contact does not pull; a sensor's offset), the indentation
/// below 0 as 0 (a gap), the acceleration as its magnitude |a|. Pressure under each of `areas`
/// (a dome's models need the indentation: an error names `area_flag`). Without an indentation
/// the transferred energy is F²/(2K) with the body spring `body_spring_n_per_m` \[N/m\]
/// ([`EnergyBasis::BodySpringAtPeakForce`]).
pub fn measured_severity(
    trace: &MeasuredTrace,
    areas: &[ContactAreaModel],
    body_spring_n_per_m: f64,
    area_flag: &str,
) -> Result<MeasuredSeverity, Error> {
    let force: Vec<f64> = trace.force_n.iter().map(|f| f.max(0.0)).collect();
    let indentation: Vec<f64> = match &trace.indentation_m {
        Some(d) => d.iter().map(|d| d.max(0.0)).collect(),
        None => {
            if let Some(dome) = areas
                .iter()
                .find(|a| !matches!(a, ContactAreaModel::Fixed { .. }))
            {
                return Err(Error::InvalidArgument {
                    arg: area_flag.into(),
                    value: match dome {
                        ContactAreaModel::HertzSphere { .. } => "hertz-sphere",
                        _ => "thin-layer",
                    }
                    .into(),
                    allowed: "a dome's contact area grows with the indentation, and the trace \
                              has no indentation column: add one (e.g. \"delta [mm]\") or give \
                              a fixed area (--contact-area, e.g. 1cm2)"
                        .into(),
                });
            }
            vec![0.0; force.len()]
        }
    };
    let acceleration: Option<Vec<f64>> = trace
        .acceleration_mps2
        .as_ref()
        .map(|a| a.iter().map(|a| a.abs()).collect());
    let s = flexrig_safety::severity(
        &ContactTraces {
            times: &trace.times_s,
            force: &force,
            indentation: &indentation,
            head_acceleration: acceleration.as_deref(),
        },
        areas,
    )?;
    let (energy, basis, work) = match trace.indentation_m {
        Some(_) => (
            s.energy_transferred_j,
            EnergyBasis::ForceAndIndentation,
            Some(s.contact_work_j),
        ),
        None => (
            spring_energy_at_force(s.peak_force_n, body_spring_n_per_m)?,
            EnergyBasis::BodySpringAtPeakForce,
            None,
        ),
    };
    Ok(MeasuredSeverity {
        peak_force_n: s.peak_force_n,
        time_of_peak_force_s: s.time_of_peak_force_s,
        pressure: s.pressure,
        energy_transferred_j: energy,
        energy_transferred_from: basis,
        contact_work_j: work,
        peak_acceleration_mps2: s.peak_acceleration_mps2,
        peak_acceleration_g: s.peak_acceleration_g,
        hic15: s.hic15,
        hic36: s.hic36,
    })
}

/// One measured impact to judge, SI units.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TraceInput {
    /// The CSV file of the trace (`--trace`).
    pub trace: PathBuf,
    /// Body region key of the body model (`--region`).
    pub region: String,
    /// A specific area of the region for the pressure limit (`--area`); absent: its most
    /// sensitive area.
    #[serde(default)]
    pub area: Option<String>,
    /// Transient or quasi-static contact (`--contact`).
    pub contact: ContactKind,
    /// The contact-area model of the pressure (`--area-model`, `--radius`, `--contact-area`);
    /// absent: pressure not assessed (a measured trace has no known geometry).
    #[serde(default)]
    pub area_model: Option<ContactAreaModel>,
}

/// The verdict on a measured impact against the region's limits.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MeasuredVerdict {
    /// True when the peak force and (when assessed) the peak mean pressure are within their
    /// limits.
    pub pass: bool,
    /// 1 − peak force / force limit (negative when exceeded).
    pub force_margin: f64,
    /// 1 − peak mean pressure / pressure limit (absent: pressure not assessed).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pressure_margin: Option<f64>,
    /// The limit closer to being reached (or further beyond): `force` or `pressure`; with the
    /// pressure not assessed, `force`.
    pub governing: flexrig_safety::GoverningLimit,
    /// Whether the pressure was judged (false without a contact-area model).
    pub pressure_assessed: bool,
}

/// The answer on a measured impact: what was read, the limits, the severity and the verdict.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MeasuredReport {
    /// The trace file, as given.
    pub trace: String,
    /// Samples read.
    pub samples: usize,
    /// From the first to the last sample \[s\].
    pub duration_s: f64,
    /// The columns read, with their units as written.
    pub columns: Vec<TraceColumn>,
    /// Columns of the header that were ignored.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub ignored_columns: Vec<String>,
    /// Body region key.
    pub region: String,
    /// Body region name.
    pub region_name: String,
    /// The specific area whose pressure limit applies.
    pub area: String,
    /// Contact kind.
    pub contact: ContactKind,
    /// Body spring K of Table A.3 \[N/m\].
    pub body_stiffness_n_per_m: f64,
    /// Force limit \[N\] (Table A.2).
    pub force_limit_n: f64,
    /// Pressure limit of the area \[Pa\] (Table A.2).
    pub pressure_limit_pa: f64,
    /// The energy the region's body spring stores at the force limit, F_max²/(2K) \[J\]
    /// (ISO/TS 15066:2016 Eq. A.1): the standard's energy criterion, for comparison with the
    /// transferred energy (the verdict judges force and pressure).
    pub energy_limit_j: f64,
    /// The contact-area model (absent: pressure not assessed).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub area_model: Option<ContactAreaModel>,
    /// The severity of the trace.
    pub severity: MeasuredSeverity,
    /// The verdict.
    pub verdict: MeasuredVerdict,
    /// What is valid but looks like a mistake.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<Warning>,
}

/// Judges the measured impact of `input` against its region's limits in the ISO/TS 15066:2016
/// body model (or `model`, a user's table): reads the trace, computes its severity
/// ([`measured_severity`]) and the verdict. Transient contact with the skull, forehead or face
/// is refused with the clause (judge it as quasi-static contact to see its severity).
pub fn judge_trace(input: &TraceInput, model: Option<&BodyModel>) -> Result<MeasuredReport, Error> {
    let bundled;
    let model = match model {
        Some(m) => m,
        None => {
            bundled = BodyModel::iso_ts_15066_2016()?;
            &bundled
        }
    };
    let region = model.region(&input.region)?;
    let area = match &input.area {
        Some(name) => region.area(name)?,
        None => region.most_sensitive_area(),
    };
    let limits = region.limits(Some(area), input.contact)?;
    if let Some(a) = &input.area_model {
        a.validate().map_err(|e| Error::InvalidArgument {
            arg: "--area-model".into(),
            value: format!("{a:?}"),
            allowed: e.to_string(),
        })?;
    }
    let trace = read_trace("--trace", &input.trace)?;
    let areas: Vec<ContactAreaModel> = input.area_model.into_iter().collect();
    let k = region.spring_constant();
    let severity = measured_severity(&trace, &areas, k, "--area-model")?;
    let force_margin = 1.0 - severity.peak_force_n / limits.force;
    let pressure_margin = match (severity.pressure.first(), limits.pressure) {
        (Some(p), Some(limit)) => Some(1.0 - p.mean_pa / limit),
        _ => None,
    };
    let governing = match pressure_margin {
        Some(p) if p < force_margin => flexrig_safety::GoverningLimit::Pressure,
        _ => flexrig_safety::GoverningLimit::Force,
    };
    let mut warnings = area_warnings(input.area_model.as_ref(), "--contact-area", "--radius");
    if !trace.ignored_columns.is_empty() {
        warnings.push(Warning {
            field: "--trace".into(),
            message: format!(
                "columns not used: {} (read are time, force, acceleration and indentation, \
                 each named with its unit)",
                trace.ignored_columns.join(", ")
            ),
        });
    }
    let most_negative = trace.force_n.iter().fold(0.0f64, |m, &f| m.min(f));
    if most_negative < -0.01 * severity.peak_force_n {
        warnings.push(Warning {
            field: "--trace".into(),
            message: format!(
                "the force falls to {} N, more than 1 % of the peak below zero: a sensor offset \
                 or a sign reversed? Forces below 0 count as 0",
                display_number(most_negative)
            ),
        });
    }
    let n = trace.times_s.len();
    Ok(MeasuredReport {
        trace: input.trace.display().to_string(),
        samples: n,
        duration_s: trace.times_s[n - 1] - trace.times_s[0],
        columns: trace.columns.clone(),
        ignored_columns: trace.ignored_columns.clone(),
        region: region.key().to_string(),
        region_name: region.name().to_string(),
        area: area.name().to_string(),
        contact: input.contact,
        body_stiffness_n_per_m: k,
        force_limit_n: limits.force,
        pressure_limit_pa: region.pressure_limit(area, input.contact)?,
        energy_limit_j: spring_energy_at_force(limits.force, k)?,
        area_model: input.area_model,
        verdict: MeasuredVerdict {
            pass: force_margin >= 0.0 && pressure_margin.is_none_or(|p| p >= 0.0),
            force_margin,
            pressure_margin,
            governing,
            pressure_assessed: pressure_margin.is_some(),
        },
        severity,
        warnings,
    })
}

/// The energy a contact of law `law` stores at the force `force` \[N\]: ∫₀^δ f dδ = k δ^{n+1}/(n+1)
/// at δ = (f/k)^{1/n} \[J\] — the energy transferred to the body at a peak force, the loading
/// work of an undamped contact (with the standard's body spring, n = 1 and k = K, F²/(2K),
/// ISO/TS 15066:2016 Eq. A.1).
pub fn contact_energy_at_force(law: &flexrig_contact::Hertz, force: f64) -> f64 {
    law.energy(law.indentation(force))
}
