//! `scenethesis generate`: a prompt in, a simulation-ready scene folder out.

use std::io::IsTerminal;
use std::path::PathBuf;
use std::time::Duration;

use anyhow::{Context, Result};
use indicatif::{ProgressBar, ProgressStyle};
use scenethesis_models::{AnswerListener, AnswerProgress};
use scenethesis_pipeline::{
    export_folder, time_limit_from_secs, FixedPlanner, Format, GenerateOptions, HousePlanFile,
    OutputDir, Pipeline, Progress, Stage, DEFAULT_TIME_LIMIT,
};
use scenethesis_scene_graph::OpenState;
use scenethesis_setup::PipelineSettings;

/// Arguments of `scenethesis generate`.
#[derive(Debug, clap::Args)]
pub struct GenerateArgs {
    /// What to build, e.g. "a cozy living room with reading materials" (or give --plan, or a
    /// --guide-image with its masks and depth alone: the scene the image shows).
    #[arg(required_unless_present_any = ["plan", "guide_image"], conflicts_with = "plan")]
    pub prompt: Option<String>,
    /// Build from a saved (possibly hand-edited) plan instead of a prompt: the JSON that
    /// `scenethesis plan` writes (docs/plan.md). The plan's prompt is the scene's prompt.
    #[arg(long, value_name = "PLAN_JSON")]
    pub plan: Option<PathBuf>,
    /// Output folder; written atomically. An earlier scenethesis output there is replaced once
    /// the new scene is complete; a folder holding anything else is refused (see --force), and
    /// a file is never replaced.
    #[arg(long)]
    pub out: PathBuf,
    /// Replace the --out folder even when it holds files scenethesis did not write.
    #[arg(long)]
    pub force: bool,
    /// Seed: the same prompt and seed give the same scene.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Pipeline options shared with `batch`.
    #[command(flatten)]
    pub pipeline: PipelineArgs,
    /// Guide selection and guidance files.
    #[command(flatten)]
    pub guide: super::guide::GuideArgs,
    /// Also write these formats into the folder (comma-separated: usd, mjcf, urdf).
    #[arg(long, value_delimiter = ',')]
    pub export: Vec<Format>,
    /// Exit with an error when the judge does not accept the final scene; a rejected scene
    /// then never replaces an accepted one already in --out.
    #[arg(long)]
    pub strict: bool,
}

/// The options of `generate` and `batch` that set up the pipeline.
#[derive(Debug, clap::Args)]
pub struct PipelineArgs {
    /// How many times the judge may re-plan a rejected scene.
    #[arg(long, default_value_t = 3)]
    pub max_replans: usize,
    /// Wall-clock budget of one scene, in seconds (0: none). Checked before every stage: when
    /// it is spent the best scene so far is kept (re-planning stops), or the run fails if it
    /// has none yet; `generate` also ends a stage that overruns it by a minute.
    #[arg(long, value_name = "SECONDS", default_value_t = DEFAULT_TIME_LIMIT.as_secs_f64(),
          value_parser = parse_time_limit)]
    pub time_limit: f64,
    /// Do not render preview images.
    #[arg(long)]
    pub no_preview: bool,
    /// The state doors, drawers and lids are left in: closed, random (fixed by the seed) or
    /// open (90 % of each joint's range, the share the judge keeps free).
    #[arg(long, value_name = "STATE", default_value = "closed",
          value_parser = |s: &str| s.parse::<OpenState>())]
    pub open_state: OpenState,
    /// Bring your own assets: a folder of GLB/glTF/OBJ files (described by an optional
    /// `assets.json`); they are preferred over the built-in generators of their category.
    #[arg(long, value_name = "DIR")]
    pub assets: Option<PathBuf>,
    /// Planner, judge and model provider selection (offline by default).
    #[command(flatten)]
    pub providers: super::providers::ProviderArgs,
}

impl PipelineArgs {
    /// The generation options these flags ask for.
    pub fn options(&self) -> GenerateOptions {
        GenerateOptions {
            max_replans: self.max_replans,
            previews: !self.no_preview,
            time_limit: time_limit_from_secs(self.time_limit).expect("checked by clap"),
            open_state: self.open_state,
            ..GenerateOptions::default()
        }
    }

    /// The library's settings these flags ask for.
    pub fn settings(&self) -> PipelineSettings {
        PipelineSettings {
            previews: !self.no_preview,
            assets: self.assets.clone(),
            providers: self.providers.settings(),
        }
    }

    /// The pipeline over the built-in library plus the `--assets` folder, with previews unless
    /// `--no-preview`, and the planner and judge the provider flags select (offline by default).
    /// Import warnings and a missing renderer are printed as warnings.
    pub fn pipeline(&self) -> Result<Pipeline> {
        let built = self.settings().build()?;
        for warning in &built.warnings {
            eprintln!("warning: {}", scenethesis_scene_graph::printable(warning));
        }
        for note in &built.notes {
            eprintln!("{note}");
        }
        Ok(built.pipeline)
    }
}

/// `--time-limit`: seconds, from 0 (none) to a week.
fn parse_time_limit(text: &str) -> Result<f64, String> {
    let seconds: f64 = text
        .trim()
        .parse()
        .map_err(|_| format!("expected a number of seconds, found `{text}`"))?;
    time_limit_from_secs(seconds).map(|_| seconds)
}

/// How long past its time limit a stage of `generate` may run before the process ends it: the
/// limit is checked between stages, and this bounds a stage that does not return.
const OVERRUN_GRACE: Duration = Duration::from_secs(60);

/// Ends the process with an error when the run is still generating `OVERRUN_GRACE` after
/// `limit`; nothing has been written by then (the output folder is swapped in only after).
/// Dropping the returned guard disarms it.
fn watchdog(limit: Option<Duration>) -> Option<WatchdogGuard> {
    let limit = limit?;
    let armed = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(true));
    let flag = armed.clone();
    std::thread::spawn(move || {
        std::thread::sleep(limit + OVERRUN_GRACE);
        if flag.load(std::sync::atomic::Ordering::SeqCst) {
            eprintln!(
                "error: the run overran its time limit of {} s by {} s inside one stage and was \
                 stopped; nothing was written (raise --time-limit)",
                limit.as_secs_f64(),
                OVERRUN_GRACE.as_secs()
            );
            std::process::exit(1);
        }
    });
    Some(WatchdogGuard(armed))
}

/// Disarms the [`watchdog`] when dropped.
struct WatchdogGuard(std::sync::Arc<std::sync::atomic::AtomicBool>);

impl Drop for WatchdogGuard {
    fn drop(&mut self) {
        self.0.store(false, std::sync::atomic::Ordering::SeqCst);
    }
}

/// How often a plain-lines progress says how much of a model's answer has arrived.
const ANSWER_LINE_EVERY: Duration = Duration::from_secs(15);

/// Draws one spinner per stage on a terminal, or plain lines otherwise; while a model's answer
/// streams in, the spinner (or a line every 15 s) says how much has arrived.
#[derive(Default)]
pub struct StageProgress {
    bar: Option<ProgressBar>,
    interactive: bool,
}

impl StageProgress {
    /// Progress on stderr: spinners on a terminal, plain lines otherwise.
    pub fn on_stderr() -> Self {
        Self {
            bar: None,
            interactive: std::io::stderr().is_terminal(),
        }
    }
}

fn label(stage: Stage, round: usize) -> String {
    if round == 0 {
        format!("{stage:<8}")
    } else {
        format!("{stage:<8} (re-plan {round})")
    }
}

impl Progress for StageProgress {
    fn stage_started(&mut self, stage: Stage, round: usize) {
        if self.interactive {
            let bar = ProgressBar::new_spinner();
            bar.set_style(
                ProgressStyle::with_template("{spinner:.cyan} {msg} {elapsed:.dim}")
                    .expect("valid template"),
            );
            bar.set_message(label(stage, round));
            bar.enable_steady_tick(Duration::from_millis(100));
            self.bar = Some(bar);
        }
    }

    fn answer_listener(&mut self, stage: Stage, round: usize) -> Option<AnswerListener> {
        let label = label(stage, round);
        let received = |p: &AnswerProgress| {
            format!(
                "{} characters of the answer received",
                scenethesis_models::grouped(p.characters)
            )
        };
        if let Some(bar) = self.bar.clone() {
            return Some(Box::new(move |p: &AnswerProgress| {
                bar.set_message(format!("{label} {}", received(p)));
            }));
        }
        // Plain lines (logs of unattended runs): one every ANSWER_LINE_EVERY at most.
        let mut last = Duration::ZERO;
        Some(Box::new(move |p: &AnswerProgress| {
            if p.elapsed >= last + ANSWER_LINE_EVERY {
                last = p.elapsed;
                eprintln!(
                    "… {label} {} in {:.0} s",
                    received(p),
                    p.elapsed.as_secs_f64()
                );
            }
        }))
    }

    fn stage_finished(&mut self, stage: Stage, round: usize, elapsed: Duration, note: &str) {
        let line = format!(
            "✔ {} {:>7.2} s  {note}",
            label(stage, round),
            elapsed.as_secs_f64()
        );
        match self.bar.take() {
            Some(bar) => {
                bar.set_style(ProgressStyle::with_template("{msg}").expect("valid template"));
                bar.finish_with_message(line);
            }
            None => eprintln!("{line}"),
        }
    }
}

/// Runs `scenethesis generate`.
pub fn run(args: GenerateArgs) -> Result<()> {
    // Every input is read and checked first (an --assets folder's manifest included), so a
    // malformed one leaves nothing behind, not even --out's missing parent folders; then the
    // output path, before the long work.
    let mut pipeline = args.pipeline.pipeline()?;
    let photo_alone = args.prompt.is_none() && args.plan.is_none();
    let (guided, photo) = args
        .guide
        .apply(pipeline, &args.pipeline.providers, photo_alone)?;
    pipeline = guided;
    if let Some(photo) = &photo {
        for line in &photo.inferred {
            eprintln!("inferred: {line}");
        }
    }
    // A plan with `rooms` is a house's floor plan (checked here, before anything is written).
    let house = match &args.plan {
        Some(path) => HousePlanFile::from_file(path)
            .with_context(|| format!("reading the plan {}", path.display()))?,
        None => None,
    };
    let prompt = match (&args.plan, &house) {
        (_, Some(house)) => house.prompt.clone(),
        (Some(path), None) => {
            let planner = FixedPlanner::from_file(path)?;
            let prompt = planner.as_plan().prompt.clone();
            pipeline = pipeline.with_planner(planner);
            prompt
        }
        (None, None) => match &photo {
            Some(photo) => photo.prompt.clone(),
            None => args.prompt.clone().unwrap_or_default(),
        },
    };
    let out = OutputDir::prepare(&args.out, args.force)?;
    let options = args.pipeline.options();
    let mut progress = StageProgress::on_stderr();
    let guard = watchdog(options.time_limit);
    let generated = match &house {
        Some(house) => pipeline.generate_house(house, args.seed, &options, &mut progress),
        None => pipeline.generate(&prompt, args.seed, &options, &mut progress),
    };
    let mut generated = generated.with_context(|| match &args.plan {
        Some(path) => format!("generating from the plan {}", path.display()),
        None => format!("generating \"{prompt}\""),
    })?;
    drop(guard);
    if let Some(photo) = photo {
        // What the image alone decided, beside the planner's own assumptions.
        generated.report.assumptions.splice(0..0, photo.inferred);
    }
    println!("{}", generated.report.summary_line());
    let rejected = !generated.report.accepted;
    if rejected && !args.strict {
        // Said clearly even without --strict (which turns it into an error below).
        eprintln!(
            "warning: the judge did not accept the scene: {}",
            generated.report.verdict.reasons()
        );
    }
    if args.strict && rejected && out.holds_accepted_scene() {
        anyhow::bail!(
            "the judge did not accept the scene ({}); the accepted scene already in {} was kept \
             and nothing was written",
            generated.report.verdict.reasons(),
            args.out.display()
        );
    }
    generated.write_to(&out)?;
    let mut files = vec!["scene.glb".to_owned(), "scene.json".to_owned()];
    files.extend(generated.previews.iter().map(|(name, _)| name.clone()));
    files.push("report.json".into());
    if !args.export.is_empty() {
        let written = export_folder(out.path(), &args.export, pipeline.assets())
            .with_context(|| format!("exporting {}", args.out.display()))?;
        files.extend(
            written
                .iter()
                .filter_map(|p| p.file_name().map(|n| n.to_string_lossy().into_owned())),
        );
    }
    println!("wrote {}: {}", args.out.display(), files.join(", "));
    if args.strict && rejected {
        anyhow::bail!(
            "the judge did not accept the scene: {}",
            generated.report.verdict.reasons()
        );
    }
    Ok(())
}
