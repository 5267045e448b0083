//! The raw results of a `cargo xtask bench` run, as kept in memory and saved as JSON
//! (`docs/performance-results.json`, or `--results PATH`): the machine, the adapter, the
//! provenance and every measured frame with each method's median time and the per-pixel counts.

use std::path::Path;

use anyhow::Context as _;
use serde::{Deserialize, Serialize};
use srt_gpu::Method;

/// The exact methods and the polygon method, in the order of the tables (the image-based
/// method, timed on the static lines only, has a column of its own).
pub const METHODS: [Method; 4] = [Method::Auto, Method::Lrt, Method::Rt, Method::Polygon];

/// How a method is named in tables and reports.
#[must_use]
pub const fn method_name(method: Method) -> &'static str {
    match method {
        Method::Auto => "auto",
        Method::Lrt => "LRT",
        Method::Rt => "RT",
        Method::Polygon => "polygon",
        Method::ImageBased => "IB",
    }
}

/// One measured frame: a scene at one size.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Measurement {
    /// Median frame time of local ray tracing alone (hull footprints), ms.
    pub lrt_ms: f64,
    /// Median time of LRT's proxy pass, ms (0 where unknown).
    pub proxy_ms: f64,
    /// Median frame time of the BVH ray tracer alone, ms.
    pub rt_ms: f64,
    /// Median frame time of `auto` (each object by LRT or the ray tracer), ms.
    pub auto_ms: f64,
    /// Median frame time of the polygon method, ms.
    pub polygon_ms: f64,
    /// Median frame time of the image-based method (the paper's "IB", cube maps of the scene's
    /// `cube_map_size`), ms; `None` where it cannot draw the scene or was not timed.
    #[serde(default)]
    pub image_based_ms: Option<f64>,
    /// LRT visibility fragments per covered pixel.
    pub overdraw_hull: f64,
    /// Ray-tracer visibility fragments per covered pixel.
    pub overdraw_rt: f64,
    /// Visibility fragments of `auto` per covered pixel.
    pub overdraw_auto: f64,
    /// Pixels shaded per covered pixel (the most of the exact methods; they share the
    /// shading pass).
    pub shaded_per_pixel: f64,
}

impl Measurement {
    /// Frame time of `method`, ms.
    #[must_use]
    pub const fn ms(&self, method: Method) -> f64 {
        match method {
            Method::Auto => self.auto_ms,
            Method::Lrt => self.lrt_ms,
            Method::Rt => self.rt_ms,
            Method::Polygon => self.polygon_ms,
            Method::ImageBased => match self.image_based_ms {
                Some(ms) => ms,
                None => f64::NAN,
            },
        }
    }

    /// Frame time of `method` against the polygon method's.
    #[must_use]
    pub fn ratio_of(&self, method: Method) -> f64 {
        self.ms(method) / self.polygon_ms
    }

    /// The exact method the program uses (`auto`) against the polygon method.
    #[must_use]
    pub fn ratio(&self) -> f64 {
        self.ratio_of(Method::Auto)
    }

    /// The report's `key=value` fields of the measurement.
    #[must_use]
    pub fn fields(&self) -> String {
        format!(
            "method=auto ratio={:.2} auto_ms={:.2} lrt_ms={:.2} proxy_ms={:.2} rt_ms={:.2} polygon_ms={:.2} image_based_ms={:.2} lrt_ratio={:.2} rt_ratio={:.2} shaded_per_pixel={:.2} overdraw_auto={:.2} overdraw_hull={:.2} overdraw_rt={:.2}",
            self.ratio(),
            self.auto_ms,
            self.lrt_ms,
            self.proxy_ms,
            self.rt_ms,
            self.polygon_ms,
            self.ms(Method::ImageBased),
            self.ratio_of(Method::Lrt),
            self.ratio_of(Method::Rt),
            self.shaded_per_pixel,
            self.overdraw_auto,
            self.overdraw_hull,
            self.overdraw_rt
        )
    }
}

/// A measured frame with what it is: a static case at one size, or one frame of a sweep.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CaseResult {
    /// The case's name (`NAME@ct=T` for a sweep's frame, as `validate --bench-frames` names it).
    pub name: String,
    /// Image width, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
    /// Triangles in the scene.
    pub triangles: usize,
    /// Objects `auto` draws by the ray tracer (0: `auto` runs the same code as LRT).
    pub traced_objects: usize,
    /// What `auto` weighed of each object in this frame (its triangles, layers and seen
    /// pixels, `srt_gpu::auto::ObjectLoad`), objects without a ray tracer left out; empty in
    /// files written before it was recorded.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub objects: Vec<ObjectLoadRecord>,
    /// The times and counts.
    #[serde(flatten)]
    pub measurement: Measurement,
    /// The exact CPU reference's frame (srt-trace on all threads, its tracer made before, as
    /// a sequence of frames keeps it), median of three, ms; `None` where it was not timed (a
    /// sweep's frames, files written before it was).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cpu_ms: Option<f64>,
}

/// An object's [`srt_gpu::auto::ObjectLoad`] as the results file keeps it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ObjectLoadRecord {
    /// Its triangles.
    pub triangles: u64,
    /// Its surface over its box's.
    pub layers: f64,
    /// Layers of its box's footprints the ray tracer draws (2 from inside the box).
    #[serde(default)]
    pub box_layers: u32,
    /// About how many pixels its bounding ball's image covers.
    pub seen_pixels: f64,
}

impl From<srt_gpu::auto::ObjectLoad> for ObjectLoadRecord {
    fn from(load: srt_gpu::auto::ObjectLoad) -> Self {
        Self {
            triangles: load.triangles,
            layers: load.layers,
            box_layers: load.box_layers,
            seen_pixels: load.seen_pixels,
        }
    }
}

impl From<ObjectLoadRecord> for srt_gpu::auto::ObjectLoad {
    fn from(record: ObjectLoadRecord) -> Self {
        Self {
            triangles: record.triangles,
            layers: record.layers,
            box_layers: record.box_layers,
            seen_pixels: record.seen_pixels,
        }
    }
}

impl CaseResult {
    /// The frame as `validate --bench-frames` records it: name, width, height.
    #[must_use]
    pub fn frame(&self) -> (&str, u32, u32) {
        (&self.name, self.width, self.height)
    }

    /// The image size as `W×H`.
    #[must_use]
    pub fn size(&self) -> String {
        format!("{}×{}", self.width, self.height)
    }
}

/// One frame of a sweep: its observation time and its measurement.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SweepFrame {
    /// The observer's time ct of the frame.
    pub ct: f64,
    /// The frame as a case.
    #[serde(flatten)]
    pub case: CaseResult,
}

/// A fly-by sweep: every frame measured with one renderer.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SweepResult {
    /// The sweep's name (its scene's).
    pub name: String,
    /// The frames in order of time.
    pub frames: Vec<SweepFrame>,
}

impl SweepResult {
    /// The frame with the highest auto / polygon ratio.
    #[must_use]
    pub fn worst_frame(&self) -> Option<&SweepFrame> {
        self.frames.iter().max_by(|a, b| {
            a.case
                .measurement
                .ratio()
                .total_cmp(&b.case.measurement.ratio())
        })
    }

    /// The highest of `value` over the frames (0 for no frames).
    fn most(&self, value: impl Fn(&Measurement) -> f64) -> f64 {
        self.frames
            .iter()
            .map(|f| value(&f.case.measurement))
            .fold(0.0, f64::max)
    }

    /// The slowest frame time of `method`, ms.
    #[must_use]
    pub fn slowest(&self, method: Method) -> f64 {
        self.most(|m| m.ms(method))
    }

    /// The worst ratio of `method` against the polygon method.
    #[must_use]
    pub fn worst_ratio_of(&self, method: Method) -> f64 {
        self.most(|m| m.ratio_of(method))
    }

    /// The most pixels shaded per covered pixel of any frame.
    #[must_use]
    pub fn worst_shaded(&self) -> f64 {
        self.most(|m| m.shaded_per_pixel)
    }

    /// The median auto / polygon ratio of the frames.
    #[must_use]
    pub fn median_ratio(&self) -> f64 {
        median(
            self.frames
                .iter()
                .map(|f| f.case.measurement.ratio())
                .collect(),
        )
    }
}

/// The machine, named without its host name.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Machine {
    /// Logical CPUs available to the process.
    pub cpus: usize,
    /// Operating system and, where known, its distribution.
    pub os: String,
    /// CPU architecture.
    pub arch: String,
    /// The CPU's model name where the system gives it (empty otherwise): a software adapter's
    /// figures depend on it as much as on the adapter (the same llvmpipe ran the teaser's frame
    /// in 35 ms on one 2-core machine and in 83 ms on another).
    #[serde(default)]
    pub cpu_model: String,
}

impl Machine {
    /// How the documents name it: "2 CPUs: MODEL, OS, ARCH".
    #[must_use]
    pub fn describe(&self) -> String {
        let model = if self.cpu_model.is_empty() {
            String::new()
        } else {
            format!(": {}", self.cpu_model)
        };
        format!("{} CPUs{model}, {}, {}", self.cpus, self.os, self.arch)
    }

    /// The machine running this process.
    #[must_use]
    pub fn this() -> Self {
        let distribution = std::fs::read_to_string("/etc/os-release")
            .ok()
            .and_then(|text| {
                text.lines()
                    .find_map(|l| l.strip_prefix("PRETTY_NAME="))
                    .map(|name| name.trim_matches('"').to_owned())
            });
        let os = std::env::consts::OS;
        let cpu_model = std::fs::read_to_string("/proc/cpuinfo")
            .ok()
            .and_then(|text| {
                text.lines()
                    .filter_map(|l| l.split_once(':'))
                    .find(|(key, _)| key.trim() == "model name")
                    .map(|(_, name)| name.trim().to_owned())
            })
            .unwrap_or_default();
        Self {
            cpus: std::thread::available_parallelism().map_or(0, std::num::NonZero::get),
            os: distribution.map_or_else(|| os.to_owned(), |d| format!("{os} ({d})")),
            arch: std::env::consts::ARCH.to_owned(),
            cpu_model,
        }
    }
}

/// Everything one run measured, with where and how.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Results {
    /// The machine.
    pub machine: Machine,
    /// The adapter ([`srt_gpu::GpuContext::adapter_summary`]).
    pub adapter: String,
    /// How frames were timed (GPU timestamps or wall clock).
    pub timing: String,
    /// The commit measured ([`crate::provenance::commit`]).
    pub commit: String,
    /// The date of the run, `YYYY-MM-DD` (UTC).
    pub date: String,
    /// Frames timed per measurement (the median is taken).
    pub frames: u32,
    /// Warm-up frames per measurement before timing.
    pub warm_up: u32,
    /// Least time in ms each method's timed frames of a measurement add up to, more than
    /// `frames` frames being timed where they are short (0: exactly `frames`, as before).
    #[serde(default)]
    pub min_measured_ms: u32,
    /// Most frames timed per method where `min_measured_ms` asks for more than `frames`.
    #[serde(default)]
    pub max_frames: u32,
    /// The static cases, every size.
    pub cases: Vec<CaseResult>,
    /// The fly-by sweeps.
    pub sweeps: Vec<SweepResult>,
    /// The full-sky lines (none in results saved before they were measured).
    #[serde(default)]
    pub full_sky: Vec<FullSkyResult>,
}

/// A full-sky line: a scene in a wide projection, which the ray tracer (and `auto`) and the CPU
/// reference draw; LRT and the polygon method draw through the pinhole only.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FullSkyResult {
    /// The case's name (`validate --bench-frames` names its frame so).
    pub name: String,
    /// Image width, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
    /// Triangles in the scene.
    pub triangles: usize,
    /// Median frame time of `auto` (every object by the ray tracer), ms.
    pub auto_ms: f64,
    /// Median frame time of the ray tracer, ms.
    pub rt_ms: f64,
    /// Median time of the CPU reference's render of the frame (its BVHs built before), ms.
    pub cpu_ms: f64,
    /// Ray-tracer visibility fragments per covered pixel.
    pub overdraw_rt: f64,
    /// Pixels shaded per covered pixel.
    pub shaded_per_pixel: f64,
}

impl FullSkyResult {
    /// The report's line.
    #[must_use]
    pub fn text(&self) -> String {
        format!(
            "full_sky={} size={}x{} tris={} auto_ms={:.2} rt_ms={:.2} cpu_ms={:.2} shaded_per_pixel={:.2} overdraw_rt={:.2}",
            self.name,
            self.width,
            self.height,
            self.triangles,
            self.auto_ms,
            self.rt_ms,
            self.cpu_ms,
            self.shaded_per_pixel,
            self.overdraw_rt
        )
    }
}

impl Results {
    /// Every measured frame: the static cases, then every sweep's frames.
    pub fn all_frames(&self) -> impl Iterator<Item = &CaseResult> {
        self.cases.iter().chain(
            self.sweeps
                .iter()
                .flat_map(|s| s.frames.iter().map(|f| &f.case)),
        )
    }

    /// How many frames each measurement timed, as the documents say it: "median of … frames
    /// per measurement after … warm-up frames".
    #[must_use]
    pub fn sampling(&self) -> String {
        let timed = if self.min_measured_ms == 0 {
            format!("{} frames", self.frames)
        } else {
            format!(
                "at least {} frames (more where they are short, until each method's add up to \
                 {} ms, at most {})",
                self.frames, self.min_measured_ms, self.max_frames
            )
        };
        format!(
            "median of {timed} per measurement after {} warm-up frames",
            self.warm_up
        )
    }

    /// Writes the results as pretty-printed JSON to `path`.
    ///
    /// # Errors
    /// An unwritable file.
    pub fn save(&self, path: &Path) -> anyhow::Result<()> {
        let json = serde_json::to_string_pretty(self)?;
        std::fs::write(path, json + "\n")
            .with_context(|| format!("cannot write {}", path.display()))
    }

    /// Reads results saved by [`Results::save`].
    ///
    /// # Errors
    /// A missing or malformed file.
    pub fn load(path: &Path) -> anyhow::Result<Self> {
        let text = std::fs::read_to_string(path)
            .with_context(|| format!("cannot read {}", path.display()))?;
        serde_json::from_str(&text)
            .with_context(|| format!("{} is not a bench results file", path.display()))
    }
}

/// The median of `values` (the upper one of an even count; 0 for none).
#[must_use]
pub fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values.get(values.len() / 2).copied().unwrap_or(0.0)
}

#[cfg(test)]
pub mod tests {
    //! Hand-built results for the tests of the modules that read them.

    use super::{
        CaseResult, FullSkyResult, Machine, Measurement, Results, SweepFrame, SweepResult,
    };

    /// A measurement with the given auto, LRT and polygon times (RT twice LRT) and shading.
    #[must_use]
    pub fn measurement(auto: f64, lrt: f64, polygon: f64, shaded: f64) -> Measurement {
        Measurement {
            lrt_ms: lrt,
            proxy_ms: 0.0,
            rt_ms: 2.0 * lrt,
            auto_ms: auto,
            polygon_ms: polygon,
            image_based_ms: Some(polygon / 2.0),
            overdraw_hull: 1.5,
            overdraw_rt: 1.2,
            overdraw_auto: 1.5,
            shaded_per_pixel: shaded,
        }
    }

    /// A case at 1280×720 with no traced object.
    #[must_use]
    pub fn case(name: &str, measurement: Measurement) -> CaseResult {
        CaseResult {
            name: name.to_owned(),
            width: 1280,
            height: 720,
            triangles: 300,
            traced_objects: 0,
            objects: Vec::new(),
            measurement,
            cpu_ms: None,
        }
    }

    /// Results of two static cases and a sweep of two frames, the second at ratio 2.5.
    #[must_use]
    pub fn results() -> Results {
        let frame = |ct: f64, m| SweepFrame {
            ct,
            case: case(&format!("fly@ct={ct}"), m),
        };
        Results {
            machine: Machine {
                cpus: 2,
                os: "linux".to_owned(),
                arch: "x86_64".to_owned(),
                cpu_model: "test CPU".to_owned(),
            },
            adapter: "test adapter".to_owned(),
            timing: "wall clock".to_owned(),
            commit: "abc".to_owned(),
            date: "2026-01-01".to_owned(),
            frames: 3,
            warm_up: 2,
            min_measured_ms: 250,
            max_frames: 60,
            cases: vec![
                case("cube", measurement(10.0, 11.0, 10.0, 1.0)),
                case("spider", measurement(15.0, 15.0, 10.0, 1.0)),
            ],
            sweeps: vec![SweepResult {
                name: "fly".to_owned(),
                frames: vec![
                    frame(0.0, measurement(12.0, 12.0, 10.0, 1.0)),
                    frame(6.0, measurement(25.0, 20.0, 10.0, 1.0)),
                ],
            }],
            full_sky: vec![FullSkyResult {
                name: "sky".to_owned(),
                width: 2048,
                height: 1024,
                triangles: 300,
                auto_ms: 40.0,
                rt_ms: 40.0,
                cpu_ms: 90.0,
                overdraw_rt: 1.5,
                shaded_per_pixel: 1.0,
            }],
        }
    }

    #[test]
    fn results_survive_json() {
        let results = results();
        let json = serde_json::to_string(&results).unwrap();
        assert!(json.contains("\"name\":\"fly@ct=6\""));
        assert_eq!(serde_json::from_str::<Results>(&json).unwrap(), results);
    }

    #[test]
    fn sweeps_summarise_their_frames() {
        let results = results();
        let sweep = &results.sweeps[0];
        assert_eq!(sweep.worst_frame().unwrap().ct, 6.0);
        assert!((sweep.median_ratio() - 2.5).abs() < 1e-12);
        assert!((sweep.worst_ratio_of(srt_gpu::Method::Lrt) - 2.0).abs() < 1e-12);
        assert_eq!(results.all_frames().count(), 4);
    }

    #[test]
    fn the_sampling_is_said_as_it_was_run_and_older_files_still_load() {
        let mut results = results();
        assert_eq!(
            results.sampling(),
            "median of at least 3 frames (more where they are short, until each method's add \
             up to 250 ms, at most 60) per measurement after 2 warm-up frames"
        );
        // A file written before the adaptive sampling and the CPU's model lacks their fields.
        let mut json: serde_json::Value = serde_json::to_value(&results).unwrap();
        let object = json.as_object_mut().unwrap();
        object.remove("min_measured_ms");
        object.remove("max_frames");
        object["machine"]
            .as_object_mut()
            .unwrap()
            .remove("cpu_model");
        let old: Results = serde_json::from_value(json).unwrap();
        assert_eq!(
            old.sampling(),
            "median of 3 frames per measurement after 2 warm-up frames"
        );
        assert_eq!(old.machine.cpu_model, "");
        results.min_measured_ms = 0;
        results.max_frames = 0;
        results.machine.cpu_model.clear();
        assert_eq!(old, results);
    }
}
