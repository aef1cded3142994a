//! Benchmark results as tables (aligned text, Markdown, CSV) and JSON, for
//! the terminal and for export.

use crate::describe::{millis, si};
use crate::measure::benchmark::Measurement;

/// Which columns a table shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Columns {
    /// One row per structure: build cost and work per ray.
    Structures,
    /// The course's timing matrix: the features of each row, then its times.
    Matrix,
}

/// Output formats of a table.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Format {
    /// Columns aligned with spaces, for the terminal.
    Text,
    Markdown,
    Csv,
    Json,
}

/// One column: a header, a readable cell (SI suffixes, units in the
/// header) and a raw cell (plain numbers, for CSV).
struct Column {
    header: &'static str,
    pretty: fn(&Measurement) -> String,
    raw: fn(&Measurement) -> String,
}

/// A switch as the course's tables word it.
pub(crate) fn yes_no(b: bool) -> String {
    if b { "yes" } else { "no" }.to_string()
}

const ACCEL: Column = Column {
    header: "accel",
    pretty: |m| m.case.settings.accel.name().into(),
    raw: |m| m.case.settings.accel.name().into(),
};
const FRAME: Column = Column {
    header: "frame ms",
    pretty: |m| format!("{:.1}", millis(m.median())),
    raw: |m| format!("{:.3}", millis(m.median())),
};
const RANGE: Column = Column {
    header: "min..max ms",
    pretty: |m| format!("{:.1}..{:.1}", millis(m.min()), millis(m.max())),
    raw: |m| format!("{:.3}..{:.3}", millis(m.min()), millis(m.max())),
};
const MAD: Column = Column {
    header: "MAD ms",
    pretty: |m| format!("{:.1}", millis(m.mad())),
    raw: |m| format!("{:.3}", millis(m.mad())),
};
const RAYS: Column = Column {
    header: "rays",
    pretty: |m| si(m.rays() as f64),
    raw: |m| m.rays().to_string(),
};
const RAYS_PER_SECOND: Column = Column {
    header: "rays/s",
    pretty: |m| si(m.rays_per_second()),
    raw: |m| format!("{:.0}", m.rays_per_second()),
};

/// The columns `which` names, in order.
fn columns(which: Columns) -> Vec<Column> {
    match which {
        Columns::Structures => vec![
            ACCEL,
            Column {
                header: "build ms",
                pretty: |m| format!("{:.2}", millis(m.index.build_time)),
                raw: |m| format!("{:.3}", millis(m.index.build_time)),
            },
            Column {
                header: "memory",
                pretty: |m| format!("{}B", si(m.index.memory_bytes as f64)),
                raw: |m| m.index.memory_bytes.to_string(),
            },
            FRAME,
            RANGE,
            MAD,
            RAYS,
            RAYS_PER_SECOND,
            Column {
                header: "tests/ray",
                pretty: |m| format!("{:.2}", m.tests_per_ray()),
                raw: |m| format!("{:.4}", m.tests_per_ray()),
            },
            Column {
                header: "nodes/ray",
                pretty: |m| format!("{:.2}", m.steps_per_ray()),
                raw: |m| format!("{:.4}", m.steps_per_ray()),
            },
        ],
        Columns::Matrix => vec![
            ACCEL,
            Column {
                header: "soft shadows",
                pretty: |m| yes_no(m.case.settings.soft_shadows),
                raw: |m| yes_no(m.case.settings.soft_shadows),
            },
            Column {
                header: "anti-aliasing",
                pretty: aa_cell,
                raw: aa_cell,
            },
            Column {
                header: "depth of field",
                pretty: dof_cell,
                raw: dof_cell,
            },
            Column {
                header: "samples/px",
                pretty: |m| m.case.settings.samples_per_pixel().to_string(),
                raw: |m| m.case.settings.samples_per_pixel().to_string(),
            },
            FRAME,
            RANGE,
            MAD,
            RAYS,
            RAYS_PER_SECOND,
        ],
    }
}

/// "N=4" with anti-aliasing, as the course report's column header has it.
fn aa_cell(m: &Measurement) -> String {
    let s = &m.case.settings;
    if s.antialiasing {
        format!("yes (N={})", s.samples)
    } else {
        "no".into()
    }
}

/// "-" without anti-aliasing, as in the course report's table (DOF
/// was only measured with AA).
fn dof_cell(m: &Measurement) -> String {
    let s = &m.case.settings;
    match (s.depth_of_field, s.antialiasing) {
        (true, _) => format!("yes (aperture {})", m.lens.aperture),
        (false, true) => "no".into(),
        (false, false) => "-".into(),
    }
}

/// The rows in `format`.
pub(crate) fn table(rows: &[Measurement], which: Columns, format: Format) -> String {
    let cols = columns(which);
    let headers: Vec<String> = cols.iter().map(|c| c.header.to_string()).collect();
    let cells = |raw: bool| -> Vec<Vec<String>> {
        rows.iter()
            .map(|m| {
                cols.iter()
                    .map(|c| if raw { (c.raw)(m) } else { (c.pretty)(m) })
                    .collect()
            })
            .collect()
    };
    match format {
        Format::Text => text(&headers, &cells(false)),
        Format::Markdown => markdown(&headers, &cells(false)),
        Format::Csv => csv(&headers, &cells(true)),
        Format::Json => json(rows),
    }
}

/// Left-aligned first column, the rest right-aligned, two spaces apart.
pub(crate) fn text(headers: &[String], rows: &[Vec<String>]) -> String {
    let widths: Vec<usize> = (0..headers.len())
        .map(|i| {
            rows.iter()
                .map(|r| r[i].len())
                .chain([headers[i].len()])
                .max()
                .unwrap_or(0)
        })
        .collect();
    let line = |cells: &[String]| {
        cells
            .iter()
            .zip(&widths)
            .enumerate()
            .map(|(i, (c, &w))| {
                if i == 0 {
                    format!("{c:<w$}")
                } else {
                    format!("{c:>w$}")
                }
            })
            .collect::<Vec<_>>()
            .join("  ")
            .trim_end()
            .to_string()
    };
    std::iter::once(line(headers))
        .chain(rows.iter().map(|r| line(r)))
        .map(|l| l + "\n")
        .collect()
}

/// A Markdown table, numbers right-aligned.
pub(crate) fn markdown(headers: &[String], rows: &[Vec<String>]) -> String {
    let line = |cells: &[String]| format!("| {} |\n", cells.join(" | "));
    let rule = format!(
        "|{}|\n",
        (0..headers.len())
            .map(|i| if i == 0 { "---" } else { "---:" })
            .collect::<Vec<_>>()
            .join("|")
    );
    line(headers) + &rule + &rows.iter().map(|r| line(r)).collect::<String>()
}

/// RFC 4180: fields with a comma, quote or line break are quoted.
pub(crate) fn csv(headers: &[String], rows: &[Vec<String>]) -> String {
    let field = |f: &String| {
        if f.contains([',', '"', '\n']) {
            format!("\"{}\"", f.replace('"', "\"\""))
        } else {
            f.clone()
        }
    };
    std::iter::once(headers)
        .chain(rows.iter().map(Vec::as_slice))
        .map(|r| r.iter().map(field).collect::<Vec<_>>().join(",") + "\n")
        .collect()
}

/// Every row with every number, times in seconds.
fn json(rows: &[Measurement]) -> String {
    let rows: Vec<serde_json::Value> = rows
        .iter()
        .map(|m| {
            let s = &m.case.settings;
            let c = &m.stats.counters;
            m.with_timing_json(serde_json::json!({
                "label": m.case.label,
                "accel": s.accel.name(),
                "grid_multiplier": m.index.grid_multiplier,
                "soft_shadows": s.soft_shadows,
                "antialiasing": s.antialiasing,
                "depth_of_field": s.depth_of_field,
                "n": s.samples,
                "aperture": m.lens.aperture,
                "focal": m.lens.focal,
                "width": s.width,
                "height": s.height,
                "samples_per_pixel": s.samples_per_pixel(),
                "mad_seconds": m.mad().as_secs_f64(),
                "eye_rays": c.eye_rays,
                "shadow_rays": c.shadow_rays,
                "reflection_rays": c.reflection_rays,
                "refraction_rays": c.refraction_rays,
                "intersection_tests": c.intersection_tests,
                "nodes_visited": c.nodes_visited,
            }))
        })
        .collect();
    serde_json::to_string_pretty(&rows).unwrap_or_default() + "\n"
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_markdown_and_csv_layouts() {
        let headers = vec!["a".to_string(), "long header".to_string()];
        let rows = vec![vec!["x, y".to_string(), "1".to_string()]];
        assert_eq!(
            text(&headers, &rows),
            "a     long header\nx, y            1\n"
        );
        assert_eq!(
            markdown(&headers, &rows),
            "| a | long header |\n|---|---:|\n| x, y | 1 |\n"
        );
        assert_eq!(csv(&headers, &rows), "a,long header\n\"x, y\",1\n");
    }
}
