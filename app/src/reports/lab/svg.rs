//! Charts as inline SVG written by hand: a bar chart with whiskers and a
//! line chart, the two shapes the report needs. Text stays text, so the
//! charts print sharp and can be searched.

use std::fmt::Write as _;

use super::html::escape;

/// One horizontal bar: a value with a low..high whisker.
pub(crate) struct Bar {
    pub(crate) label: String,
    pub(crate) value: f64,
    pub(crate) low: f64,
    pub(crate) high: f64,
    pub(crate) colour: [u8; 3],
}

fn rgb([r, g, b]: [u8; 3]) -> String {
    format!("rgb({r},{g},{b})")
}

/// A number with three significant digits at most, for ticks and labels.
pub(crate) fn short(v: f64) -> String {
    match v.abs() {
        0.0 => "0".into(),
        a if a >= 100.0 => format!("{v:.0}"),
        a if a >= 10.0 => format!("{v:.1}"),
        a if a >= 1.0 => format!("{v:.2}"),
        _ => format!("{v:.3}"),
    }
}

/// Horizontal bars, one per row, on one linear scale from 0, each with its
/// value written after it; `unit` names the axis.
pub(crate) fn bar_chart(bars: &[Bar], unit: &str) -> String {
    const LABEL: f64 = 190.0;
    const ROW: f64 = 18.0;
    const WIDTH: f64 = 760.0;
    let plot = WIDTH - LABEL - 70.0;
    let top = bars
        .iter()
        .map(|b| b.high.max(b.value))
        .fold(0.0_f64, f64::max)
        .max(1e-12);
    let height = ROW * bars.len() as f64 + 40.0;
    let x = |v: f64| LABEL + plot * (v / top).clamp(0.0, 1.0);
    let mut out = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{WIDTH}\" height=\"{height}\" \
         viewBox=\"0 0 {WIDTH} {height}\" role=\"img\">\n"
    );
    for (i, bar) in bars.iter().enumerate() {
        let y = 6.0 + ROW * i as f64;
        let _ = writeln!(
            out,
            "<text x=\"{}\" y=\"{}\" font-size=\"11\" text-anchor=\"end\">{}</text>\
             <rect x=\"{LABEL}\" y=\"{y}\" width=\"{:.1}\" height=\"{}\" fill=\"{}\"/>\
             <line x1=\"{:.1}\" x2=\"{:.1}\" y1=\"{}\" y2=\"{}\" stroke=\"#222\"/>\
             <text x=\"{:.1}\" y=\"{}\" font-size=\"10\">{}</text>",
            LABEL - 6.0,
            y + ROW * 0.65,
            escape(&bar.label),
            x(bar.value) - LABEL,
            ROW - 4.0,
            rgb(bar.colour),
            x(bar.low),
            x(bar.high),
            y + (ROW - 4.0) / 2.0,
            y + (ROW - 4.0) / 2.0,
            x(bar.high.max(bar.value)) + 4.0,
            y + ROW * 0.65,
            short(bar.value)
        );
    }
    let axis = ROW * bars.len() as f64 + 10.0;
    let _ = writeln!(
        out,
        "<line x1=\"{LABEL}\" x2=\"{}\" y1=\"{axis}\" y2=\"{axis}\" stroke=\"#888\"/>",
        LABEL + plot
    );
    for i in 0..=4 {
        let v = top * f64::from(i) / 4.0;
        let _ = writeln!(
            out,
            "<text x=\"{:.1}\" y=\"{}\" font-size=\"10\" text-anchor=\"middle\">{}</text>",
            x(v),
            axis + 13.0,
            short(v)
        );
    }
    let _ = writeln!(
        out,
        "<text x=\"{:.1}\" y=\"{}\" font-size=\"11\" text-anchor=\"middle\">{}</text>\n</svg>",
        LABEL + plot / 2.0,
        axis + 27.0,
        escape(unit)
    );
    out
}

/// One line of a line chart.
pub(crate) struct Series {
    pub(crate) name: String,
    pub(crate) colour: [u8; 3],
    pub(crate) points: Vec<(f64, f64)>,
}

/// Where a line chart's y axis starts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum YAxis {
    /// At 0 (or the lowest value when one is negative): amounts such as
    /// times and errors, whose ratios the chart should show.
    FromZero,
    /// Just below the lowest value: decibels, where 0 means nothing and
    /// the differences between curves are what is read.
    Fitted,
}

/// A line chart of `series` on linear axes, each point marked, with a
/// legend in the top-right corner, or the bottom-right when a point lies
/// under the top one.
pub(crate) fn line_chart(
    title: &str,
    x_label: &str,
    y_label: &str,
    y_axis: YAxis,
    series: &[Series],
) -> String {
    const W: f64 = 360.0;
    const H: f64 = 240.0;
    const LEFT: f64 = 52.0;
    const BOTTOM: f64 = 40.0;
    const TOP: f64 = 24.0;
    let all = || series.iter().flat_map(|s| s.points.iter().copied());
    let (x0, x1) = all().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), (x, _)| {
        (a.min(x), b.max(x))
    });
    let lowest = match y_axis {
        YAxis::FromZero => 0.0_f64,
        YAxis::Fitted => f64::INFINITY,
    };
    let (y0, y1) = all().fold((lowest, f64::NEG_INFINITY), |(a, b), (_, y)| {
        (a.min(y), b.max(y))
    });
    let y0 = match y_axis {
        YAxis::Fitted if y0.is_finite() && y1 > y0 => y0 - 0.05 * (y1 - y0),
        YAxis::Fitted if y0.is_finite() => y0 - 1.0,
        YAxis::Fitted => 0.0,
        YAxis::FromZero => y0,
    };
    let (x0, x1) = if x0.is_finite() && x1 > x0 {
        (x0, x1)
    } else {
        (x0.min(0.0), x0.max(0.0) + 1.0)
    };
    let y1 = if y1.is_finite() && y1 > y0 {
        y1
    } else {
        y0 + 1.0
    };
    let (pw, ph) = (W - LEFT - 12.0, H - TOP - BOTTOM);
    let px = |x: f64| LEFT + pw * (x - x0) / (x1 - x0);
    let py = |y: f64| TOP + ph * (1.0 - (y - y0) / (y1 - y0));
    let mut out = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{W}\" height=\"{H}\" \
         viewBox=\"0 0 {W} {H}\" role=\"img\">\n\
         <text x=\"{}\" y=\"15\" font-size=\"12\" text-anchor=\"middle\" font-weight=\"bold\">{}</text>\n\
         <rect x=\"{LEFT}\" y=\"{TOP}\" width=\"{pw}\" height=\"{ph}\" fill=\"none\" stroke=\"#888\"/>\n",
        W / 2.0,
        escape(title)
    );
    for i in 0..=4 {
        let t = f64::from(i) / 4.0;
        let (xv, yv) = (x0 + t * (x1 - x0), y0 + t * (y1 - y0));
        let _ = writeln!(
            out,
            "<text x=\"{:.1}\" y=\"{}\" font-size=\"10\" text-anchor=\"middle\">{}</text>\
             <text x=\"{}\" y=\"{:.1}\" font-size=\"10\" text-anchor=\"end\">{}</text>",
            px(xv),
            TOP + ph + 13.0,
            short(xv),
            LEFT - 4.0,
            py(yv) + 3.0,
            short(yv)
        );
    }
    let _ = writeln!(
        out,
        "<text x=\"{:.1}\" y=\"{}\" font-size=\"11\" text-anchor=\"middle\">{}</text>\
         <text x=\"12\" y=\"{:.1}\" font-size=\"11\" text-anchor=\"middle\" \
         transform=\"rotate(-90 12 {:.1})\">{}</text>",
        LEFT + pw / 2.0,
        H - 6.0,
        escape(x_label),
        TOP + ph / 2.0,
        TOP + ph / 2.0,
        escape(y_label)
    );
    // The legend's entries, 13 px apart, right-aligned in a corner free
    // of points.
    const LEGEND_WIDTH: f64 = 110.0;
    let rows = series.len() as f64;
    let under_top_legend =
        all().any(|(x, y)| px(x) >= W - LEGEND_WIDTH - 4.0 && py(y) <= TOP + 12.0 + 13.0 * rows);
    let legend_top = if under_top_legend {
        TOP + ph - 13.0 * rows
    } else {
        TOP + 12.0
    };
    for (i, s) in series.iter().enumerate() {
        let colour = rgb(s.colour);
        let path: Vec<String> = s
            .points
            .iter()
            .map(|&(x, y)| format!("{:.1},{:.1}", px(x), py(y)))
            .collect();
        let _ = writeln!(
            out,
            "<polyline points=\"{}\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"2\"/>",
            path.join(" ")
        );
        for &(x, y) in &s.points {
            let _ = write!(
                out,
                "<circle cx=\"{:.1}\" cy=\"{:.1}\" r=\"3\" fill=\"{colour}\"/>",
                px(x),
                py(y)
            );
        }
        let ly = legend_top + 13.0 * i as f64;
        let _ = writeln!(
            out,
            "<rect x=\"{}\" y=\"{:.1}\" width=\"10\" height=\"3\" fill=\"{colour}\"/>\
             <text x=\"{}\" y=\"{:.1}\" font-size=\"10\">{}</text>",
            W - LEGEND_WIDTH,
            ly - 4.0,
            W - 96.0,
            ly,
            escape(&s.name)
        );
    }
    out.push_str("</svg>\n");
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The y axis's tick labels, bottom to top.
    fn y_ticks(svg: &str) -> Vec<String> {
        svg.split("text-anchor=\"end\">")
            .skip(1)
            .map(|s| s[..s.find('<').unwrap()].to_string())
            .collect()
    }

    /// The y of the legend's first entry.
    fn legend_y(svg: &str, name: &str) -> f64 {
        let before = &svg[..svg.find(&format!(">{name}</text>")).unwrap()];
        let y = &before[before.rfind("y=\"").unwrap() + 3..];
        y[..y.find('"').unwrap()].parse().unwrap()
    }

    fn rising(from: f64) -> Series {
        Series {
            name: "rising".into(),
            colour: [0, 0, 0],
            points: (0..5)
                .map(|i| (f64::from(i), from + f64::from(i)))
                .collect(),
        }
    }

    #[test]
    fn a_fitted_axis_starts_below_the_lowest_value_not_at_zero() {
        let series = [rising(30.0)];
        let from_zero = y_ticks(&line_chart("t", "x", "y", YAxis::FromZero, &series));
        let fitted = y_ticks(&line_chart("t", "x", "y", YAxis::Fitted, &series));
        assert_eq!(from_zero.first().map(String::as_str), Some("0"));
        let lowest: f64 = fitted[0].parse().unwrap();
        assert!((29.0..30.0).contains(&lowest), "{fitted:?}");
        assert_eq!(
            fitted.last(),
            from_zero.last(),
            "the top is the highest value"
        );
    }

    #[test]
    fn the_legend_leaves_the_corner_a_curve_ends_in() {
        let falling = Series {
            name: "falling".into(),
            colour: [0, 0, 0],
            points: (0..5)
                .map(|i| (f64::from(i), 10.0 - f64::from(i)))
                .collect(),
        };
        let top = legend_y(
            &line_chart("t", "x", "y", YAxis::FromZero, &[falling]),
            "falling",
        );
        let bottom = legend_y(
            &line_chart("t", "x", "y", YAxis::FromZero, &[rising(0.0)]),
            "rising",
        );
        assert!(top < 50.0 && bottom > 150.0, "{top} {bottom}");
    }
}
