//! Section 7, against the course's numbers: when the scene is the course's
//! `balls_medium`, the times its report gave beside ours, row by row.

use tracer::accel::AccelKind;

use super::html::{escape, table, titled_section};
use super::{Lab, ms};
use crate::measure::benchmark::SamplingColumn;

/// One row of the course's timing table.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct CourseRow {
    pub(crate) grid: bool,
    pub(crate) soft_shadows: bool,
    pub(crate) sampling: SamplingColumn,
    /// The reported time, in seconds (the report writes "≅ 1.03s").
    pub(crate) seconds: f64,
}

const fn row(grid: bool, soft_shadows: bool, sampling: SamplingColumn, seconds: f64) -> CourseRow {
    CourseRow {
        grid,
        soft_shadows,
        sampling,
        seconds,
    }
}

/// Where [`COURSE_TIMES`] comes from.
pub(crate) const COURSE_CITATION: &str = "P. Rodrigues, M. Duarte, Y. Cheng, \"3D Programming\", \
    assignment 1 report, group 11, Master in Computer Science and Engineering, University of \
    Lisbon, 19 April 2020, Figure 5.1 \"Executions Time\" (file balls_medium.p3f, \
    anti-aliasing N = 4)";

/// The course's Figure 5.1, in its order: execution times of
/// `balls_medium.p3f` without and with the grid, hard and soft shadows,
/// one sample, anti-aliasing, anti-aliasing with depth of field. See
/// [`COURSE_CITATION`].
pub(crate) const COURSE_TIMES: [CourseRow; 12] = [
    row(false, false, SamplingColumn::Single, 1.03),
    row(false, false, SamplingColumn::Antialiasing, 14.45),
    row(false, false, SamplingColumn::AntialiasingDof, 14.82),
    row(false, true, SamplingColumn::Single, 2.23),
    row(false, true, SamplingColumn::Antialiasing, 16.51),
    row(false, true, SamplingColumn::AntialiasingDof, 16.84),
    row(true, false, SamplingColumn::Single, 0.77),
    row(true, false, SamplingColumn::Antialiasing, 12.01),
    row(true, false, SamplingColumn::AntialiasingDof, 12.20),
    row(true, true, SamplingColumn::Single, 1.75),
    row(true, true, SamplingColumn::Antialiasing, 14.50),
    row(true, true, SamplingColumn::AntialiasingDof, 13.99),
];

/// The course's scene, by file name.
const COURSE_SCENE: &str = "balls_medium";

/// Whether `scene_name` (a path or a label) names the course's scene.
pub(crate) fn is_course_scene(scene_name: &str) -> bool {
    std::path::Path::new(scene_name)
        .file_stem()
        .and_then(|s| s.to_str())
        .is_some_and(|s| s.eq_ignore_ascii_case(COURSE_SCENE))
}

fn sampling_words(s: SamplingColumn) -> &'static str {
    match s {
        SamplingColumn::Single => "one sample",
        SamplingColumn::Antialiasing => "AA",
        SamplingColumn::AntialiasingDof => "AA + DOF",
    }
}

pub(crate) fn section(lab: &Lab) -> String {
    if !is_course_scene(&lab.request.scene_name) {
        let body = format!(
            "<p>The course measured only <code>{COURSE_SCENE}</code>; this report is of another \
             scene, so there is nothing to set beside it. Run the report on \
             <code>scenes/{COURSE_SCENE}.p3f</code> to compare.</p>\n"
        );
        return titled_section("course", "7. Against the course's numbers", &body);
    }
    let rows: Vec<(String, Vec<String>)> = COURSE_TIMES
        .iter()
        .filter_map(|c| {
            let accel = if c.grid {
                AccelKind::Grid
            } else {
                AccelKind::None
            };
            let ours = lab.row(accel, c.soft_shadows, c.sampling)?;
            let ours_s = ours.median().as_secs_f64();
            Some((
                ours.case.file_stem(),
                vec![
                    accel.name().into(),
                    if c.soft_shadows { "yes" } else { "no" }.into(),
                    sampling_words(c.sampling).into(),
                    format!("{:.2}", c.seconds),
                    ms(ours.median()),
                    format!("{:.1}x", c.seconds / ours_s.max(1e-9)),
                ],
            ))
        })
        .collect();
    let caveat = if lab.request.quick
        || (lab.base.width, lab.base.height) != (lab.request.base.width, lab.request.base.height)
    {
        format!(
            "<p class=\"how\"><strong>Not like for like:</strong> this report rendered {} x {} \
             pixels, not the scene's {} x {}; the speed-ups are of a smaller image.</p>\n",
            lab.base.width, lab.base.height, lab.request.base.width, lab.request.base.height
        )
    } else {
        String::new()
    };
    let body = format!(
        "<p>The course's reported times beside ours, each row's speed-up being the course's time \
         over our median. The course's machine, threads and runs are not known: its times are \
         single measurements as printed.</p>\n{}{caveat}<p class=\"how\">Source: {}. Ours: \
         median of {} run(s) on {} thread(s).</p>\n",
        table(
            "course",
            &[
                "structure",
                "soft shadows",
                "sampling",
                "course s",
                "ours ms",
                "speed-up"
            ],
            &rows
        ),
        escape(COURSE_CITATION),
        lab.runs,
        lab.threads
    );
    titled_section("course", "7. Against the course's numbers", &body)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_course_table_is_the_matrix_without_the_bvh() {
        let base = tracer::render::RenderSettings::default();
        let matrix = crate::measure::benchmark::matrix(
            &base,
            &tracer::scene::Viewpoint::default(),
            &[AccelKind::None, AccelKind::Grid],
            tracer::render::Encoding::Linear,
        );
        let ours: Vec<(bool, bool, SamplingColumn)> = matrix
            .iter()
            .map(|c| {
                let s = &c.settings;
                (
                    s.accel == AccelKind::Grid,
                    s.soft_shadows,
                    SamplingColumn::of(s),
                )
            })
            .collect();
        let course: Vec<_> = COURSE_TIMES
            .iter()
            .map(|c| (c.grid, c.soft_shadows, c.sampling))
            .collect();
        assert_eq!(ours, course);
        assert!(is_course_scene("scenes/balls_medium.p3f"));
        assert!(!is_course_scene("scenes/balls_high.p3f"));
    }
}
