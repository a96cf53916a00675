//! Loading the ONNX Runtime shared library and running models through it.

use std::path::{Path, PathBuf};
use std::sync::{mpsc, Mutex, OnceLock};

use ort::environment::Environment;
use ort::session::Session;
use ort::value::{Tensor, ValueType};

use crate::error::{OnnxError, DYLIB_ENV};

/// The process-wide ONNX Runtime: the library path it was loaded from and its environment.
static LOADED: OnceLock<(PathBuf, Environment)> = OnceLock::new();
/// Serialises the first load, so two threads cannot load two different libraries.
static LOADING: Mutex<()> = Mutex::new(());

/// A handle on the ONNX Runtime library loaded into this process.
///
/// ONNX Runtime can be loaded once per process: a second [`Runtime::load`] with the same path
/// returns the same runtime, one with a different path is an error naming both.
#[derive(Clone)]
pub struct Runtime {
    library: PathBuf,
    environment: Environment,
}

impl std::fmt::Debug for Runtime {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Runtime")
            .field("library", &self.library)
            .finish()
    }
}

impl Runtime {
    /// Loads the library named by the `ORT_DYLIB_PATH` environment variable.
    pub fn from_env() -> Result<Self, OnnxError> {
        match std::env::var_os(DYLIB_ENV) {
            Some(path) if !path.is_empty() => Self::load(PathBuf::from(path)),
            _ => Err(OnnxError::LibraryNotSet),
        }
    }

    /// Loads the ONNX Runtime shared library at `path` (for example the `pip install
    /// onnxruntime` wheel's `onnxruntime/capi/libonnxruntime.so.1.xx.y`). The library must be
    /// ONNX Runtime 1.17 or newer.
    pub fn load(path: impl AsRef<Path>) -> Result<Self, OnnxError> {
        let path = path.as_ref();
        let library_error = |message: String| OnnxError::Library {
            path: path.to_path_buf(),
            message,
        };
        if !path.is_file() {
            return Err(library_error("no such file".into()));
        }
        let canonical = path
            .canonicalize()
            .map_err(|e| library_error(format!("cannot resolve the path: {e}")))?;
        let _guard = LOADING.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((loaded, environment)) = LOADED.get() {
            if *loaded != canonical {
                return Err(library_error(format!(
                    "this process already loaded ONNX Runtime from {}, and a process can load \
                     it only once",
                    loaded.display()
                )));
            }
            return Ok(Self {
                library: loaded.clone(),
                environment: environment.clone(),
            });
        }
        let builder = ort::init_from(&canonical).map_err(|e| library_error(e.to_string()))?;
        let environment = builder
            .with_name("scenethesis")
            .build()
            .map_err(|e| library_error(format!("cannot create an environment: {e}")))?;
        let (library, environment) = LOADED.get_or_init(|| (canonical, environment));
        Ok(Self {
            library: library.clone(),
            environment: environment.clone(),
        })
    }

    /// The library this runtime was loaded from (canonical path).
    pub fn library(&self) -> &Path {
        &self.library
    }
}

/// A float32 tensor crossing the runtime boundary: shape and row-major data.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct TensorF32 {
    pub shape: Vec<i64>,
    pub data: Vec<f32>,
}

/// What a model declares about one input or output.
#[derive(Debug, Clone)]
pub(crate) struct Port {
    pub name: String,
    /// Dimensions, `-1` where dynamic; `None` when the port is not a tensor.
    pub shape: Option<Vec<i64>>,
    /// Whether the element type is float32.
    pub float32: bool,
}

impl Port {
    fn from_outlet(name: &str, dtype: &ValueType) -> Self {
        Self {
            name: name.to_string(),
            shape: dtype.tensor_shape().map(|s| s.to_vec()),
            float32: dtype.tensor_type() == Some(ort::value::TensorElementType::Float32),
        }
    }

    /// `[d0, d1, …]` with `?` for dynamic dimensions.
    pub fn describe(&self) -> String {
        match &self.shape {
            None => format!("`{}` (not a tensor)", self.name),
            Some(dims) => format!(
                "`{}` {}[{}]",
                self.name,
                if self.float32 {
                    "float32"
                } else {
                    "non-float32"
                },
                dims.iter()
                    .map(|d| if *d < 0 { "?".into() } else { d.to_string() })
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        }
    }
}

/// A request to a model's worker thread: named inputs, wanted outputs, where to answer.
struct Job {
    inputs: Vec<(String, TensorF32)>,
    outputs: Vec<String>,
    reply: mpsc::Sender<Result<Vec<TensorF32>, String>>,
}

/// An opened model. `ort` sessions are not `Send`, so each model's session lives on a worker
/// thread of its own that runs one request at a time; the thread ends when the model is
/// dropped.
pub(crate) struct Model {
    pub path: PathBuf,
    pub inputs: Vec<Port>,
    pub outputs: Vec<Port>,
    jobs: Mutex<mpsc::Sender<Job>>,
}

impl Model {
    /// Opens `path` in `runtime`.
    pub fn open(runtime: &Runtime, path: &Path) -> Result<Self, OnnxError> {
        let model_error = |message: String| OnnxError::Model {
            path: path.to_path_buf(),
            message,
        };
        if !path.is_file() {
            return Err(model_error("no such file".into()));
        }
        let (jobs, queue) = mpsc::channel::<Job>();
        let (ready, opened) = mpsc::channel::<Result<(Vec<Port>, Vec<Port>), String>>();
        let environment = runtime.environment.clone();
        let file = path.to_path_buf();
        std::thread::Builder::new()
            .name(format!("onnx {}", crate::model_stem(path)))
            .spawn(move || {
                let session = Session::builder(&environment)
                    .map_err(|e| e.to_string())
                    .and_then(|mut b| b.commit_from_file(&file).map_err(|e| e.to_string()));
                let mut session = match session {
                    Ok(session) => session,
                    Err(e) => {
                        let _ = ready.send(Err(e));
                        return;
                    }
                };
                let ports = |outlets: &[ort::value::Outlet]| {
                    outlets
                        .iter()
                        .map(|o| Port::from_outlet(o.name(), o.dtype()))
                        .collect::<Vec<_>>()
                };
                let _ = ready.send(Ok((ports(session.inputs()), ports(session.outputs()))));
                for job in queue {
                    let _ = job.reply.send(run(&mut session, job.inputs, &job.outputs));
                }
            })
            .map_err(|e| model_error(format!("cannot start its worker thread: {e}")))?;
        let (inputs, outputs) = opened
            .recv()
            .map_err(|_| model_error("its worker thread stopped while opening it".into()))?
            .map_err(model_error)?;
        Ok(Self {
            path: path.to_path_buf(),
            inputs,
            outputs,
            jobs: Mutex::new(jobs),
        })
    }

    /// The input named `name`.
    pub fn input(&self, name: &str) -> Option<&Port> {
        self.inputs.iter().find(|p| p.name == name)
    }

    /// The output named `name`.
    pub fn output(&self, name: &str) -> Option<&Port> {
        self.outputs.iter().find(|p| p.name == name)
    }

    /// Runs the model on named float32 inputs and returns the named float32 outputs in order.
    pub fn run(
        &self,
        inputs: Vec<(String, TensorF32)>,
        outputs: &[&str],
    ) -> Result<Vec<TensorF32>, String> {
        let (reply, answer) = mpsc::channel();
        let job = Job {
            inputs,
            outputs: outputs.iter().map(|s| s.to_string()).collect(),
            reply,
        };
        self.jobs
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .send(job)
            .map_err(|_| "the model's worker thread has stopped".to_string())?;
        answer
            .recv()
            .map_err(|_| "the model's worker thread stopped while running it".to_string())?
    }
}

/// One inference on the worker thread.
fn run(
    session: &mut Session,
    inputs: Vec<(String, TensorF32)>,
    outputs: &[String],
) -> Result<Vec<TensorF32>, String> {
    let mut values = Vec::with_capacity(inputs.len());
    for (name, tensor) in inputs {
        let shape = tensor.shape.clone();
        let value = Tensor::from_array((tensor.shape, tensor.data))
            .map_err(|e| format!("cannot make input `{name}` of shape {shape:?}: {e}"))?;
        values.push((name, value));
    }
    let results = session
        .run(values)
        .map_err(|e| format!("ONNX Runtime failed: {e}"))?;
    outputs
        .iter()
        .map(|name| {
            let value = results
                .get(name)
                .ok_or_else(|| format!("the model produced no output `{name}`"))?;
            let (shape, data) = value
                .try_extract_tensor::<f32>()
                .map_err(|e| format!("output `{name}` is not a float32 tensor: {e}"))?;
            Ok(TensorF32 {
                shape: shape.to_vec(),
                data: data.to_vec(),
            })
        })
        .collect()
}
