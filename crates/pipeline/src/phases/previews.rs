//! Render: previews of the chosen attempt, when asked for and a renderer is configured. A
//! renderer failure is a note in the report, not an error.

use scenethesis_render_api::{render_previews, SceneRenderer};

use super::clock::StageClock;
use super::judge::Attempt;
use crate::stage::Stage;
use crate::GenerateOptions;

/// The chosen attempt's previews (file name, PNG bytes) and notes on what was skipped.
pub(crate) fn previews(
    renderer: Option<&dyn SceneRenderer>,
    best: &Attempt,
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
    let rendered = clock.run_infallible(
        Stage::Render,
        best.round,
        || render_previews(renderer, &best.scene, &best.meshes, options.preview_size),
        |result| {
            let count = result.as_ref().map_or(0, Vec::len);
            format!("{count} image(s) with {}", renderer.name())
        },
    );
    match rendered {
        Ok(images) => (images, Vec::new()),
        Err(e) => (Vec::new(), vec![format!("previews skipped: {e}")]),
    }
}
