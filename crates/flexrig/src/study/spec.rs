//! What a sweep varies: `PATH=SPEC` dimensions and the points they span.
//!
//! SPEC is a list (`0.1,0.2,0.5`, `cj,cl`, or a TOML array `[0.1, 0.2]`), a linear range
//! `start:stop:count` (both ends included), a logarithmic range `start:stop:count:log`, a file
//! `@values.txt` (one value per line, `#` comments), or a single value. The points are the full
//! grid (the first dimension varies slowest) or, zipped, the dimensions side by side.

use flexrig_rig::Override;
use flexrig_rig::overrides::parse_value;

use crate::Error;

/// Most points of one sweep.
pub const MAX_POINTS: usize = 10_000_000;

/// Largest `@file` of values \[bytes\] (ten million short values).
pub const MAX_VALUE_FILE_BYTES: u64 = 256 * 1024 * 1024;

/// Most points one process runs (their rows are kept in memory, a few hundred bytes each):
/// larger sweeps are split into shards.
pub const MAX_POINTS_PER_PROCESS: usize = 1_000_000;

/// Refuses running `count` points in one process when that is more than
/// [`MAX_POINTS_PER_PROCESS`], naming `arg` (the user's flag or argument).
pub fn check_process_points(arg: &str, count: usize) -> Result<(), Error> {
    if count > MAX_POINTS_PER_PROCESS {
        return Err(bad(
            arg,
            &format!("{count} points"),
            &format!(
                "one process runs at most {MAX_POINTS_PER_PROCESS} points (their rows are kept \
                 in memory): split the sweep into shards (flexrig sweep --shard i/N, or from \
                 Python a Dask client)"
            ),
        ));
    }
    Ok(())
}

/// One varied scene field and its values.
#[derive(Debug, Clone, PartialEq)]
pub struct Dimension {
    /// Dotted scene path, e.g. `robot.payload_kg`.
    pub path: String,
    /// The values, in order.
    pub values: Vec<toml::Value>,
}

fn bad(arg: &str, value: &str, allowed: &str) -> Error {
    let value = if value.chars().count() > 120 {
        format!("{}…", value.chars().take(120).collect::<String>())
    } else {
        value.to_string()
    };
    Error::InvalidArgument {
        arg: arg.into(),
        value,
        allowed: allowed.into(),
    }
}

impl Dimension {
    /// Parses `PATH=SPEC` (see the module documentation); `read` reads an `@file`. At most
    /// [`MAX_POINTS`] values.
    pub fn parse(text: &str, read: &dyn Fn(&str) -> Result<String, Error>) -> Result<Self, Error> {
        Self::parse_within(text, read, MAX_POINTS)
    }

    /// Parses `PATH=SPEC` with at most `budget` values: the count of a range, a list or a file
    /// is checked before any value is made, so a huge grid is refused at once.
    pub fn parse_within(
        text: &str,
        read: &dyn Fn(&str) -> Result<String, Error>,
        budget: usize,
    ) -> Result<Self, Error> {
        let Some((path, spec)) = text.split_once('=') else {
            return Err(bad(
                "--set",
                text,
                "must be PATH=SPEC, e.g. robot.payload_kg=0.1,0.2,0.5 or \
                 operator.start.release_angle_deg=10:60:11",
            ));
        };
        // the path is checked like a single override
        let path = Override::parse(&format!("{path}=0"))?.path;
        let spec = spec.trim();
        let arg = format!("--set {path}");
        let over = |count: usize| {
            bad(
                &arg,
                spec,
                &format!(
                    "gives {count} values; with the other --set values the grid may have at \
                     most {MAX_POINTS} points, so this one at most {budget}"
                ),
            )
        };
        let values = if let Some(file) = spec.strip_prefix('@') {
            if file.trim().is_empty() {
                return Err(bad(&arg, spec, "@ needs a file name, e.g. @values.txt"));
            }
            let text = read(file).map_err(|e| bad(&arg, spec, &e.to_string()))?;
            let lines = || {
                text.lines()
                    .map(str::trim)
                    .filter(|l| !l.is_empty() && !l.starts_with('#'))
            };
            let count = lines().count();
            if count > budget {
                return Err(over(count));
            }
            lines().map(parse_value).collect()
        } else if let Some(range) = parse_range(spec, &arg, budget)? {
            range
        } else {
            match parse_value(spec) {
                toml::Value::Array(items) => items,
                _ if spec.starts_with('{') || spec.starts_with('"') => vec![parse_value(spec)],
                _ => {
                    let count = spec.split(',').count();
                    if count > budget {
                        return Err(over(count));
                    }
                    spec.split(',').map(|v| parse_value(v.trim())).collect()
                }
            }
        };
        if values.len() > budget {
            return Err(over(values.len()));
        }
        if values.is_empty() {
            return Err(bad(
                &arg,
                spec,
                "gives no values (an empty list, range or file)",
            ));
        }
        Ok(Dimension { path, values })
    }
}

/// Parses the `PATH=SPEC` texts of one sweep: the grid's (or the zip's) point count is checked
/// against [`MAX_POINTS`] dimension by dimension before the values are made, and a field varied
/// twice (the same path, or a path inside another's table) is refused.
pub fn parse_all(
    set: &[String],
    read: &dyn Fn(&str) -> Result<String, Error>,
    zip: bool,
) -> Result<Vec<Dimension>, Error> {
    let mut dimensions: Vec<Dimension> = Vec::with_capacity(set.len());
    let mut product = 1usize;
    for text in set {
        let budget = if zip {
            MAX_POINTS
        } else {
            MAX_POINTS / product
        };
        let d = Dimension::parse_within(text, read, budget)?;
        product = product.saturating_mul(d.values.len());
        dimensions.push(d);
    }
    check_distinct(&dimensions)?;
    Ok(dimensions)
}

/// Refuses two dimensions on one field: the same path, or one path inside the other's table
/// (`operator.start` and `operator.start.release_angle_deg`): the later override would replace
/// the earlier one's value, and the table would claim values that never ran.
pub fn check_distinct(dimensions: &[Dimension]) -> Result<(), Error> {
    for (i, a) in dimensions.iter().enumerate() {
        for b in &dimensions[..i] {
            let inside = |outer: &str, inner: &str| {
                inner
                    .strip_prefix(outer)
                    .is_some_and(|rest| rest.is_empty() || rest.starts_with('.'))
            };
            if inside(&a.path, &b.path) || inside(&b.path, &a.path) {
                let how = if a.path == b.path {
                    format!(
                        "is varied twice: give all its values in one --set, e.g. {}=0.1,0.2",
                        a.path
                    )
                } else {
                    format!(
                        "overlaps --set {}: one field would override the other's values; vary \
                         each field once",
                        b.path
                    )
                };
                return Err(bad(&format!("--set {}", a.path), &a.path, &how));
            }
        }
    }
    Ok(())
}

/// `start:stop:count[:log]` as values, `None` if `spec` is not a range.
fn parse_range(spec: &str, arg: &str, budget: usize) -> Result<Option<Vec<toml::Value>>, Error> {
    let parts: Vec<&str> = spec.split(':').collect();
    let number = |s: &str| s.trim().parse::<f64>().ok().filter(|v| v.is_finite());
    // a value with a colon is meant as a range (no scene value has one): a malformed range
    // gets the range syntax, not a type error about the text
    let syntax = "a range is FROM:TO:N with both ends included, e.g. 10:60:11, or \
                  FROM:TO:N:log, e.g. 1e-3:1:25:log; a list is 0.1,0.2,0.5";
    if parts.len() < 2 || spec.starts_with('{') || spec.starts_with('"') || spec.starts_with('[') {
        return Ok(None);
    }
    if !(parts.len() == 3 || (parts.len() == 4 && parts[3].trim() == "log")) {
        return Err(bad(arg, spec, syntax));
    }
    let (Some(start), Some(stop)) = (number(parts[0]), number(parts[1])) else {
        return Err(bad(arg, spec, syntax));
    };
    // a count too large for usize is refused like any count over the budget
    let count: usize = parts[2]
        .trim()
        .parse::<u128>()
        .map(|c| c.min(usize::MAX as u128) as usize)
        .map_err(|_| {
            bad(
                arg,
                spec,
                "start:stop:count needs a whole number of points, e.g. 10:60:11",
            )
        })?;
    if count == 0 || count > budget {
        return Err(bad(
            arg,
            spec,
            &format!(
                "the count must lie in [1, {budget}] (an empty range has no points; the whole \
                 grid has at most {MAX_POINTS})"
            ),
        ));
    }
    let log = parts.len() == 4;
    if log && !(start > 0.0 && stop > 0.0) {
        return Err(bad(arg, spec, "a log range needs start > 0 and stop > 0"));
    }
    let at = |i: usize| {
        if count == 1 {
            return start;
        }
        let s = i as f64 / (count - 1) as f64;
        if log {
            (start.ln() + s * (stop.ln() - start.ln())).exp()
        } else {
            start + s * (stop - start)
        }
    };
    Ok(Some(
        (0..count)
            .map(|i| {
                // land exactly on the ends
                let v = if i + 1 == count { stop } else { at(i) };
                toml::Value::Float(v)
            })
            .collect(),
    ))
}

/// Number of points of the dimensions: the product (grid) or the common length (zip).
pub fn point_count(dimensions: &[Dimension], zip: bool) -> Result<usize, Error> {
    if dimensions.is_empty() {
        return Ok(1);
    }
    if zip {
        let n = dimensions[0].values.len();
        if let Some(d) = dimensions.iter().find(|d| d.values.len() != n) {
            return Err(bad(
                "--zip",
                &format!("{} has {} values", d.path, d.values.len()),
                &format!(
                    "every --set needs the same number of values to zip ({} has {n})",
                    dimensions[0].path
                ),
            ));
        }
        return Ok(n);
    }
    dimensions
        .iter()
        .try_fold(1usize, |acc, d| acc.checked_mul(d.values.len()))
        .filter(|n| *n <= MAX_POINTS)
        .ok_or_else(|| {
            bad(
                "--set",
                &dimensions
                    .iter()
                    .map(|d| format!("{}: {}", d.path, d.values.len()))
                    .collect::<Vec<_>>()
                    .join(" × "),
                &format!("the grid must have at most {MAX_POINTS} points"),
            )
        })
}

/// The overrides of point `index` (0-based, in grid or zip order).
pub fn point(dimensions: &[Dimension], zip: bool, index: usize) -> Vec<Override> {
    if zip {
        return dimensions
            .iter()
            .map(|d| Override::new(&d.path, d.values[index].clone()))
            .collect();
    }
    let mut rest = index;
    let mut out: Vec<Override> = dimensions
        .iter()
        .rev()
        .map(|d| {
            let i = rest % d.values.len();
            rest /= d.values.len();
            Override::new(&d.path, d.values[i].clone())
        })
        .collect();
    out.reverse();
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dim(text: &str) -> Dimension {
        Dimension::parse(text, &|_| Ok("1\n# c\n2\n\n3\n".into())).unwrap()
    }

    #[test]
    fn specs_give_the_documented_values() {
        let floats = |d: &Dimension| -> Vec<f64> {
            d.values
                .iter()
                .map(|v| v.as_float().or(v.as_integer().map(|i| i as f64)).unwrap())
                .collect()
        };
        assert_eq!(floats(&dim("a.b=0.1,0.2,0.5")), vec![0.1, 0.2, 0.5]);
        assert_eq!(floats(&dim("a.b=10:60:11"))[1], 15.0);
        assert_eq!(floats(&dim("a.b=10:60:11")).len(), 11);
        let log = floats(&dim("a.b=1e-3:1:4:log"));
        assert!((log[1] - 1e-2).abs() < 1e-15 && log[3] == 1.0, "{log:?}");
        assert_eq!(floats(&dim("a.b=@v.txt")), vec![1.0, 2.0, 3.0]);
        assert_eq!(dim("robot.design=cj,cl").values.len(), 2);
        assert_eq!(dim("a.b=[1, 2]").values.len(), 2);
        assert_eq!(
            dim("solver.beam={ model = \"modal\", modes = 8 }")
                .values
                .len(),
            1
        );
    }

    #[test]
    fn bad_specs_name_the_flag() {
        for spec in ["a.b=1:2:0", "a.b=0:1:3:log", "a.b", "a.b=1:2:x"] {
            let e = Dimension::parse(spec, &|_| Ok(String::new())).unwrap_err();
            assert!(e.to_string().contains("--set"), "{spec}: {e}");
        }
        let e = Dimension::parse("a.b=@empty", &|_| Ok("# nothing\n".into())).unwrap_err();
        assert!(e.to_string().contains("no values"), "{e}");
    }

    #[test]
    fn a_range_typo_gets_the_range_syntax() {
        // Regression: "0.1:1" was taken as a string and refused as "expected f64"
        for spec in ["a.b=0.1:1", "a.b=0.1:x:3", "a.b=1:2:3:lin", "a.b=1:2:3:4:5"] {
            let e = Dimension::parse(spec, &|_| Ok(String::new()))
                .unwrap_err()
                .to_string();
            assert!(
                e.contains("FROM:TO:N") && e.contains("--set a.b"),
                "{spec}: {e}"
            );
        }
        // a table or a quoted string with a colon is a value
        assert_eq!(dim("a.b=\"x:y\"").values.len(), 1);
    }

    #[test]
    fn huge_grids_are_refused_before_their_values_are_made() {
        // Regression: three large ranges were made (and checked) before the grid was counted;
        // values from a file were not counted. Each refusal below comes from counting alone:
        // 1e7 × 1e7 values would not fit in memory.
        let read = |_: &str| -> Result<String, Error> { Ok("1\n".repeat(3_000)) };
        let set = |specs: &[&str]| specs.iter().map(|s| s.to_string()).collect::<Vec<_>>();
        for (specs, zip) in [
            (
                set(&["a=0:1:10000000", "b=0:1:10000000", "c=0:1:10000000"]),
                false,
            ),
            (set(&["a=0:1:5000", "b=0:1:5000"]), false),
            (set(&["a=@big.txt", "b=@big.txt", "c=@big.txt"]), false),
            (set(&["a=0:1:20000000"]), true),
            (set(&["a=0:1:99999999999999999999999"]), false),
        ] {
            let e = parse_all(&specs, &read, zip).unwrap_err().to_string();
            assert!(
                e.contains("--set") && e.contains(&MAX_POINTS.to_string()),
                "{e}"
            );
        }
        // at the bound it is accepted: 1000 × 10000 = MAX_POINTS
        let d = parse_all(&set(&["a=0:1:1000", "b=0:1:10000"]), &read, false).unwrap();
        assert_eq!(point_count(&d, false).unwrap(), MAX_POINTS);
    }

    #[test]
    fn a_field_varied_twice_is_refused() {
        // Regression: the same path twice ran only the last values while the table claimed both
        let read = |_: &str| -> Result<String, Error> { Ok(String::new()) };
        for specs in [
            ["robot.payload_kg=0.1,0.2", "robot.payload_kg=0.3,0.4"],
            [
                "operator.start={ from = \"release\", release_angle_deg = 20.0 }",
                "operator.start.release_angle_deg=10,20",
            ],
        ] {
            let specs: Vec<String> = specs.iter().map(|s| s.to_string()).collect();
            let e = parse_all(&specs, &read, false).unwrap_err().to_string();
            assert!(e.contains("twice") || e.contains("overlaps"), "{e}");
        }
        // a path that merely starts with another's name is another field
        let specs: Vec<String> = ["a.b=1,2", "a.bc=1,2"]
            .iter()
            .map(|s| s.to_string())
            .collect();
        assert_eq!(parse_all(&specs, &read, false).unwrap().len(), 2);
    }

    #[test]
    fn grid_and_zip_enumerate_every_point_once() {
        let d = vec![dim("a=1,2,3"), dim("b=cj,cl")];
        assert_eq!(point_count(&d, false).unwrap(), 6);
        let p = point(&d, false, 4);
        assert_eq!(p[0].value, toml::Value::Integer(3));
        assert_eq!(p[1].value, toml::Value::String("cj".into()));
        assert!(point_count(&d, true).is_err());
        let z = vec![dim("a=1,2"), dim("b=cj,cl")];
        assert_eq!(point_count(&z, true).unwrap(), 2);
        assert_eq!(
            point(&z, true, 1)[1].value,
            toml::Value::String("cl".into())
        );
    }
}
