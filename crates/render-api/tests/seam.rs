//! A second renderer behind the seam: a CPU renderer that paints each view one flat colour
//! (by kind, shaded by the number of objects it can draw), and renderers that misbehave.

use std::collections::BTreeMap;

use scenethesis_imagery::{Camera, Intrinsics};
use scenethesis_render_api::{
    preview_views, render_previews, render_view, RendererError, SceneRenderer, ViewImage, ViewKind,
    ViewRequest, PREVIEW_FILES,
};
use scenethesis_scene_graph::{Architecture, Mesh, Scene};

/// Paints every view flat; `short` drops the last view, `wrong_size` draws one pixel too wide.
#[derive(Default)]
struct Flat {
    short: bool,
    wrong_size: bool,
}

fn camera(size: [u32; 2]) -> Camera {
    Camera::look_at(
        Intrinsics::from_vertical_fov(size[0], size[1], 0.9),
        [0.0, 2.0, 4.0].into(),
        [0.0, 0.0, 0.0].into(),
        nalgebra::Vector3::y(),
    )
}

impl SceneRenderer for Flat {
    fn name(&self) -> String {
        "flat".into()
    }

    fn render_views(
        &self,
        scene: &Scene,
        meshes: &BTreeMap<String, Mesh>,
        views: &[ViewRequest],
    ) -> Result<Vec<ViewImage>, RendererError> {
        let drawn = scene
            .objects
            .iter()
            .filter(|o| meshes.contains_key(&o.id))
            .count();
        let shade = (drawn * 40).min(255) as u8;
        let mut images: Vec<ViewImage> = views
            .iter()
            .map(|v| {
                let rgb = match v.kind {
                    ViewKind::Photo => [shade, 90, 40],
                    ViewKind::Top => [40, shade, 90],
                };
                let w = v.size[0] + u32::from(self.wrong_size);
                let color = image::RgbaImage::from_pixel(
                    w,
                    v.size[1],
                    image::Rgba([rgb[0], rgb[1], rgb[2], 255]),
                );
                ViewImage {
                    camera: camera(v.size),
                    color,
                }
            })
            .collect();
        if self.short {
            images.pop();
        }
        Ok(images)
    }
}

/// Refuses every scene, as a renderer that lost its device would.
struct Broken;

impl SceneRenderer for Broken {
    fn name(&self) -> String {
        "broken".into()
    }

    fn render_views(
        &self,
        _: &Scene,
        _: &BTreeMap<String, Mesh>,
        views: &[ViewRequest],
    ) -> Result<Vec<ViewImage>, RendererError> {
        Err(RendererError::View {
            renderer: self.name(),
            view: views[0].kind,
            size: views[0].size,
            source: "the device was lost".into(),
        })
    }
}

fn room() -> Scene {
    Scene::new(Architecture::rectangular_room(4.0, 3.0, 2.5, 0.9))
}

#[test]
fn previews_are_the_photo_and_square_top_views_as_png() {
    let previews = render_previews(&Flat::default(), &room(), &BTreeMap::new(), [64, 48]).unwrap();
    let names: Vec<&str> = previews.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, PREVIEW_FILES);
    let decoded: Vec<image::RgbaImage> = previews
        .iter()
        .map(|(_, png)| image::load_from_memory(png).unwrap().to_rgba8())
        .collect();
    assert_eq!(decoded[0].dimensions(), (64, 48));
    assert_eq!(decoded[1].dimensions(), (48, 48), "the top view is square");
    assert_eq!(decoded[0].get_pixel(0, 0).0, [0, 90, 40, 255]);
    assert_eq!(decoded[1].get_pixel(0, 0).0, [40, 0, 90, 255]);
    assert!(preview_views([64, 48]).iter().all(|v| v.supersample == 2));
}

#[test]
fn one_view_comes_back_with_its_camera() {
    let request = ViewRequest::new(ViewKind::Photo, [32, 24]);
    let view = render_view(&Flat::default(), &room(), &BTreeMap::new(), request).unwrap();
    assert_eq!(view.camera.intrinsics.width, 32);
    assert_eq!(view.color.dimensions(), (32, 24));
}

#[test]
fn answers_that_do_not_fit_the_request_are_refused_naming_the_renderer() {
    let short = Flat {
        short: true,
        ..Flat::default()
    };
    let err = render_previews(&short, &room(), &BTreeMap::new(), [16, 16]).unwrap_err();
    assert!(
        matches!(
            err,
            RendererError::ViewCount {
                asked: 2,
                drawn: 1,
                ..
            }
        ),
        "{err}"
    );
    assert!(
        err.to_string().contains("`flat` drew 1 image(s) for 2"),
        "{err}"
    );

    let wide = Flat {
        wrong_size: true,
        ..Flat::default()
    };
    let err = render_view(
        &wide,
        &room(),
        &BTreeMap::new(),
        ViewRequest::new(ViewKind::Top, [8, 6]),
    )
    .unwrap_err();
    assert_eq!(
        err.to_string(),
        "renderer `flat` drew the top view at 9×6 pixels; 8×6 were asked for"
    );
}

#[test]
fn a_renderers_failure_names_it_the_view_and_the_cause() {
    let err = render_previews(&Broken, &room(), &BTreeMap::new(), [16, 12]).unwrap_err();
    assert_eq!(
        err.to_string(),
        "renderer `broken` cannot draw the photo view at 16×12 pixels: the device was lost"
    );
    assert!(std::error::Error::source(&err).is_some());
}
