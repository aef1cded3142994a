//! A lesson walked as a student walks it: its scene opened, its start
//! applied, then for each step its setup, the check before the student
//! acts, the step's solution, the check after. `lesson check` asks that
//! every step fails before and passes after; the window sets a step up
//! with [`state_at_step`].

use std::path::Path;
use std::sync::Arc;

use anyhow::Result;
use tracer::scene::{Limits, ParseError, Scene, parse_scene};
use tracer::world::World;

use crate::load::{self, Loaded, SceneSource};

use super::check::Part;
use super::check::{Verdict, evaluate};
use super::format::{Lesson, LessonError, LessonErrors, LessonScene, LessonStep};
use super::state::LessonState;

/// The lesson's scene and the world built from it, the lesson's
/// references to its objects, materials and lights checked. An inline
/// scene's parse error and its objects' places name the lesson file's
/// lines; a scene file that cannot be read, the lesson's `file =` line.
pub(crate) fn open_scene(lesson: &Lesson) -> Result<(Scene, Arc<World>)> {
    let (scene, world) = load_scene(lesson)?;
    check_references(lesson, &scene, &world)?;
    Ok((scene, world))
}

fn load_scene(lesson: &Lesson) -> Result<(Scene, Arc<World>)> {
    let read = |source| Loaded::read(source, &[], &mut |_| {});
    let loaded = match &lesson.scene {
        LessonScene::Bundled(name) => read(SceneSource::Bundled(name.clone()))?,
        LessonScene::File(path) => read(SceneSource::File(path.value.clone())).map_err(|e| {
            let name = path.value.display().to_string();
            at_file_line(lesson, &name, (path.line, path.column), e)
        })?,
        LessonScene::Fetched { url, text } => read(SceneSource::Written {
            name: url.value.clone(),
            text: text.clone(),
        })
        .map_err(|e| at_file_line(lesson, &url.value, (url.line, url.column), e))?,
        LessonScene::Inline { text, first_line } => {
            let dir = Path::new(&lesson.file).parent();
            let mut scene = parse_scene(text, None, &Limits::default()).map_err(|e| {
                let command = e
                    .command
                    .as_ref()
                    .map_or_else(String::new, |c| format!("in `{c}`: "));
                LessonError {
                    file: lesson.file.clone(),
                    line: first_line + e.line.max(1) as usize - 1,
                    column: e.column.max(1) as usize,
                    message: format!("in the scene: {command}{}", e.kind),
                }
            })?;
            scene.base_dir = dir.map(Path::to_path_buf);
            // The ray tree names where each object was declared: in the
            // lesson file, as the parse errors above do.
            let offset = u32::try_from(first_line.saturating_sub(1)).unwrap_or(u32::MAX);
            for (line, _) in &mut scene.object_positions.0 {
                *line = line.saturating_add(offset);
            }
            let world = load::build_with_sky(&scene);
            return Ok((scene, Arc::new(world)));
        }
    };
    Ok((loaded.scene, loaded.world))
}

/// A scene file's error `e`: a problem with the whole file (`name`) is
/// the lesson's, at its `file =` line; a mistake inside the scene keeps
/// the scene's own place.
fn at_file_line(
    lesson: &Lesson,
    name: &str,
    (line, column): (usize, usize),
    e: anyhow::Error,
) -> anyhow::Error {
    match e.downcast_ref::<ParseError>() {
        Some(parse) if parse.line == 0 => anyhow::Error::new(LessonError {
            file: lesson.file.clone(),
            line,
            column,
            message: format!("the scene {name}: {}", parse.kind),
        }),
        _ => e.context(format!(
            "{}:{line}:{column}: the lesson's scene",
            lesson.file
        )),
    }
}

/// The state before step `step` is done: the start, every earlier step's
/// setup and solution, this step's setup; no answer given.
pub(crate) fn state_at_step(
    lesson: &Lesson,
    scene: &Scene,
    world: &Arc<World>,
    step: usize,
) -> Result<LessonState> {
    let mut state = start(lesson, scene.clone(), world.clone())?;
    for done in lesson.steps.iter().take(step) {
        enter(&mut state, done, &lesson.file)?;
        state.apply(&done.solution, &lesson.file)?;
    }
    if let Some(current) = lesson.steps.get(step) {
        enter(&mut state, current, &lesson.file)?;
    }
    Ok(state)
}

/// Every object, material and light a step's check names exists once
/// the step is solved (a solution may add a light its check reads), on the
/// side the check reads; every one that does not is an error at its
/// number in the lesson file, all of them at once.
fn check_references(lesson: &Lesson, scene: &Scene, world: &Arc<World>) -> Result<()> {
    let mut state = start(lesson, scene.clone(), world.clone())?;
    let mut errors = Vec::new();
    for step in &lesson.steps {
        enter(&mut state, step, &lesson.file)?;
        state.apply(&step.solution, &lesson.file)?;
        for reference in &step.references {
            let (part, which) = reference.value;
            // Without side B the check itself says compare mode is off.
            let Ok(side) = state.side(which) else {
                continue;
            };
            let scene = &side.scene;
            let (index, count, what) = match part {
                Part::Object(n) => (n, scene.objects.len(), "object"),
                Part::Material(n) => (n, scene.materials.len(), "material"),
                Part::Light(n) => (n, scene.lights.len(), "light"),
            };
            if index >= count {
                let numbers = match count {
                    0 => "none".to_string(),
                    1 => format!("{what} 0"),
                    _ => format!("{what}s 0 to {}", count - 1),
                };
                errors.push(LessonError {
                    file: lesson.file.clone(),
                    line: reference.line,
                    column: reference.column,
                    message: format!(
                        "no {what} {index}: once this step is solved, the scene has {numbers} \
                         (counted from 0 in the scene's order)"
                    ),
                });
            }
        }
    }
    if errors.is_empty() {
        Ok(())
    } else {
        Err(LessonErrors(errors).into())
    }
}

/// The lesson's scene with its `[start]` applied.
fn start(lesson: &Lesson, scene: Scene, world: Arc<World>) -> Result<LessonState> {
    let mut state = LessonState::new(scene, world);
    state.apply(&lesson.start, &lesson.file)?;
    Ok(state)
}

/// A step begins: its setup applied, the last step's answer forgotten.
fn enter(state: &mut LessonState, step: &LessonStep, file: &str) -> Result<()> {
    state.answer = None;
    state.apply(&step.setup, file)
}

/// One step replayed.
#[derive(Debug, Clone)]
pub(crate) struct StepReplay {
    pub(crate) title: String,
    /// The check on the step's starting state: it must not hold.
    pub(crate) before: Verdict,
    /// The check once the solution is applied: it must hold.
    pub(crate) after: Verdict,
    /// When the solution's answer is wrong, the value the workbench
    /// computed, in the format's words: for the teacher, to tell a wrong
    /// question from a wrong answer (the student's panel never shows it).
    pub(crate) computed: Option<String>,
}

impl StepReplay {
    /// `None` when the step is sound, else what is wrong with it.
    pub(crate) fn failure(&self) -> Option<String> {
        if self.before.is_done() {
            Some(format!(
                "the check already holds before the student acts ({})",
                self.before.reason()
            ))
        } else if !self.after.is_done() {
            let computed = (self.computed.as_ref())
                .map_or_else(String::new, |v| format!(" (the workbench computes {v})"));
            Some(format!(
                "the solution does not pass the check: {}{computed}",
                self.after.reason()
            ))
        } else {
            None
        }
    }
}

/// Replays every step of `lesson`, calling `on_step` as each is done. An
/// error is a lesson that cannot be walked at all (its scene does not load,
/// an edit is refused).
pub(crate) fn replay(
    lesson: &Lesson,
    on_step: &mut dyn FnMut(usize, &StepReplay),
) -> Result<Vec<StepReplay>> {
    let (scene, world) = open_scene(lesson)?;
    let mut state = start(lesson, scene, world)?;
    let mut replays = Vec::with_capacity(lesson.steps.len());
    for (i, step) in lesson.steps.iter().enumerate() {
        enter(&mut state, step, &lesson.file)?;
        let before = evaluate(&step.check.value, &state);
        state.apply(&step.solution, &lesson.file)?;
        let after = evaluate(&step.check.value, &state);
        let computed = match (&after, step.check.value.answer_of()) {
            (Verdict::Wrong(_), Some((of, side))) => Some(
                of.read(&state, side)
                    .map_or_else(|why| why, |v| of.reads().show(&v)),
            ),
            _ => None,
        };
        let replay = StepReplay {
            title: step.title.clone(),
            before,
            after,
            computed,
        };
        on_step(i, &replay);
        replays.push(replay);
    }
    Ok(replays)
}

#[cfg(test)]
mod tests;
