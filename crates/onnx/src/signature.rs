//! Checking a model's declared inputs and outputs against what a provider feeds and reads: the
//! one place the providers look ports up and word their [`OnnxError::Signature`] errors.

use crate::runtime::{Model, Port};
use crate::OnnxError;

/// A model as one provider sees it, for checking its signature. Every failure is an
/// [`OnnxError::Signature`] naming the model file.
pub(crate) struct Signature<'a> {
    model: &'a Model,
    /// What the model is to the provider, in messages: `model`, `encoder`, `decoder`.
    role: &'static str,
}

impl<'a> Signature<'a> {
    /// The signature of `model`, called `role` in messages ("the {role}'s inputs are …").
    pub fn new(model: &'a Model, role: &'static str) -> Self {
        Self { model, role }
    }

    /// A signature error saying `message`.
    pub fn error(&self, message: String) -> OnnxError {
        OnnxError::Signature {
            path: self.model.path.clone(),
            message,
        }
    }

    /// The input `name`; when the model has none, an error listing its inputs. `what` follows
    /// the name in the message (e.g. ` (a grey image [1, 1, H, W])`, or empty).
    pub fn input(&self, name: &str, what: &str) -> Result<&'a Port, OnnxError> {
        self.model.input(name).ok_or_else(|| {
            self.error(format!(
                "no input `{name}`{what}; the {}'s inputs are {}",
                self.role,
                listed(&self.model.inputs)
            ))
        })
    }

    /// The output `name`; when the model has none, an error listing its outputs.
    pub fn output(&self, name: &str) -> Result<&'a Port, OnnxError> {
        self.model.output(name).ok_or_else(|| {
            self.error(format!(
                "no output `{name}`; the {}'s outputs are {}",
                self.role,
                listed(&self.model.outputs)
            ))
        })
    }

    /// The image input: the one named `name`, or, unnamed, the model's only input. `shape`
    /// says what the image should be (e.g. `[1, 3, H, W]`) when the model has several inputs.
    pub fn image_input(&self, name: Option<&str>, shape: &str) -> Result<&'a Port, OnnxError> {
        let inputs = &self.model.inputs;
        match name {
            Some(name) => self.input(name, ""),
            None if inputs.len() == 1 => Ok(&inputs[0]),
            None => Err(self.error(format!(
                "expected one input (an image {shape}), found {}; name the image input in the \
                 configuration",
                listed(inputs)
            ))),
        }
    }

    /// The RGB image input ([`Signature::image_input`]), float32 `[1, 3, H, W]` (batch and
    /// channels may be dynamic), with its height and width (negative when dynamic). `shape`
    /// is the expected shape as messages show it (e.g. `[1, 3, H, W]`).
    pub fn rgb_input(
        &self,
        name: Option<&str>,
        shape: &str,
    ) -> Result<(&'a Port, i64, i64), OnnxError> {
        let input = self.image_input(name, shape)?;
        match input.image_dims(|c| c == 3 || c < 0) {
            Some((_, h, w)) => Ok((input, h, w)),
            None => Err(self.error(format!(
                "input {} should be float32 {shape}",
                input.describe()
            ))),
        }
    }

    /// The output named `name`, or, unnamed, the model's first output.
    pub fn output_or_first(&self, name: Option<&str>) -> Result<&'a Port, OnnxError> {
        match name {
            Some(name) => self.output(name),
            None => self
                .model
                .outputs
                .first()
                .ok_or_else(|| self.error("no outputs".into())),
        }
    }
}

impl Port {
    /// `(C, H, W)` of a float32 image port `[N, C, H, W]` whose batch `N` is 1 or dynamic and
    /// whose channel count passes `channels`; dynamic dimensions are negative. `None` for any
    /// other port.
    pub fn image_dims(&self, channels: impl Fn(i64) -> bool) -> Option<(i64, i64, i64)> {
        match self.shape.as_deref() {
            Some(&[n, c, h, w]) if self.float32 && (n == 1 || n < 0) && channels(c) => {
                Some((c, h, w))
            }
            _ => None,
        }
    }
}

/// The ports as `` `name` float32[d0, …] ``, comma-separated.
fn listed(ports: &[Port]) -> String {
    ports
        .iter()
        .map(Port::describe)
        .collect::<Vec<_>>()
        .join(", ")
}
