//! Render: previews of the chosen attempt, when asked for and a renderer is configured. Each
//! attempt's previews are drawn on a thread of their own while the judge runs
//! ([`PreviewsBeside`]); the chosen attempt's are kept, and drawn now only when its thread gave
//! none. A renderer failure is a note in the report, not an error.

use scenethesis_render_api::{render_previews, SceneRenderer};

use super::beside::{PreviewsBeside, Rendered};
use super::clock::StageClock;
use super::judge::Attempt;
use crate::stage::Stage;
use crate::GenerateOptions;

/// The chosen attempt's previews (file name, PNG bytes) and notes on what was skipped.
pub(crate) fn previews(
    renderer: Option<&dyn SceneRenderer>,
    best: &mut Attempt,
    options: &GenerateOptions,
    clock: &mut StageClock<'_>,
) -> (Vec<(String, Vec<u8>)>, Vec<String>) {
    if !options.previews {
        return (Vec::new(), Vec::new());
    }
    let Some(renderer) = renderer else {
        return (
            Vec::new(),
            vec!["previews skipped: no renderer configured".into()],
        );
    };
    let note = |result: &Rendered| {
        let count = result.as_ref().map_or(0, Vec::len);
        format!("{count} image(s) with {}", renderer.name())
    };
    let beside = best.previews_beside.take().and_then(PreviewsBeside::finish);
    let rendered = match beside {
        Some((rendered, took)) => {
            let note = format!("{}, drawn beside the judge", note(&rendered));
            clock.record(Stage::Render, best.round, took, &note);
            rendered
        }
        None => clock.run_infallible(
            Stage::Render,
            best.round,
            || render_previews(renderer, &best.scene, &best.meshes, options.preview_size),
            note,
        ),
    };
    match rendered {
        Ok(images) => (images, Vec::new()),
        Err(e) => (Vec::new(), vec![format!("previews skipped: {e}")]),
    }
}
