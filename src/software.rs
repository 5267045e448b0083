//! `auto` on a machine whose only adapter is a software rasteriser (Mesa's lavapipe and
//! llvmpipe, SwiftShader): the adapter and srt's CPU tracer then run on the same cores, and which
//! finishes a render first depends on the job. The adapter pays a fixed start (its pipelines are
//! compiled for the CPU) and an upload that grows with the scene (BVHs, footprint buffers), then
//! draws a frame in a fraction of the CPU tracer's time; the CPU tracer starts at once but pays
//! for every row. `auto` measures the CPU's cost on a few rows of the first frame
//! ([`srt_trace::Tracer::measure_frame`]), estimates both wholes ([`Estimates`]) and takes
//! the smaller ([`weigh`], which measures the rows a second time only where the first measure
//! could have misled it). The rows measured are kept in the CPU's picture. The constants were measured on the 2-core machine CI runs on, whole process
//! against whole process; docs/performance.md ("auto without a hardware GPU") gives the rule and
//! its measurements, and this module's test replays them.

use std::path::Path;

use srt_gpu::SoftwareApi;
use srt_scene::Scene;
use srt_trace::{FrameCost, FrameMeasure, RenderSettings};

/// How far ahead of the CPU a first measure may put a software adapter and still be measured
/// again ([`weigh`]): a moment in which the machine served another process can only lengthen
/// the CPU's rows, and such moments lengthened a picture's estimate by up to half on the
/// machine CI runs on (docs/performance.md, "auto without a hardware GPU").
pub const SECOND_LOOK: f64 = 1.5;

/// The most triangles a scene may have for `auto` to measure the CPU's cost while it opens the
/// GPU, not knowing yet whether the adapter is a software one: a tracer of this many builds in
/// about 0.2 s on the 2-core machine CI runs on (the 121 496-triangle 2CylinderEngine in 0.08 s),
/// time a hardware GPU's user would otherwise wait for nothing.
pub const MEASURED_WHILE_OPENING: usize = 300_000;

/// What opening a software adapter and then not using it adds to a render, at least, on the
/// 2-core machine CI runs on: `auto` that opened lavapipe and rendered on the CPU took 0.039 s
/// and 0.055 s longer than `--backend cpu` in the recorded collections (this module's test
/// reads them), the flythrough 0.04–0.08 s (lavapipe) and 0.05–0.06 s (llvmpipe GL) in
/// 2026-11-30's runs (docs/performance.md, "auto without a hardware GPU"). Before an adapter is
/// opened, `auto` opens one only where the cheapest software adapter could save more than this
/// ([`Estimates::worth_opening`]).
pub const OPENING_SECONDS: f64 = 0.035;

/// What a render asks for: the size, how many frames and how many pictures of each frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Job {
    /// The picture's size and samples.
    pub settings: RenderSettings,
    /// Frames (1 for a still).
    pub frames: u32,
    /// Pictures rendered of each frame (display colours, radiance, the time channels).
    pub passes: u32,
}

impl Job {
    /// One picture of one frame at `settings`.
    #[must_use]
    pub const fn still(settings: RenderSettings) -> Self {
        Self {
            settings,
            frames: 1,
            passes: 1,
        }
    }
}

/// What the CPU tracer costs for a job's scene, measured on this machine.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CpuCost {
    /// Seconds to build the tracer (the objects' BVHs), paid once a frame.
    pub build_seconds: f64,
    /// One picture of one frame.
    pub frame: FrameCost,
}

impl CpuCost {
    /// The cost of a frame whose tracer took `build_seconds` to build and whose picture was
    /// measured by `measure`.
    #[must_use]
    pub fn of(build_seconds: f64, measure: &FrameMeasure) -> Self {
        Self {
            build_seconds,
            frame: measure.cost(),
        }
    }

    /// What the notes report of the measure: "its tracer built in 0.0135 s, a picture traced
    /// in about 0.1912 s".
    #[must_use]
    pub fn describe(&self) -> String {
        format!(
            "its tracer built in {:.4} s, a picture traced in about {:.4} s",
            self.build_seconds,
            self.frame.seconds()
        )
    }
}

/// A software adapter's costs, whole process against whole process ([`SoftwareCosts::of`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SoftwareCosts {
    /// Seconds to start: the device opened, pipelines compiled for the CPU, targets made.
    pub start_seconds: f64,
    /// Seconds of upload per triangle (the GPU's BVHs and per-triangle buffers).
    pub triangle_seconds: f64,
    /// Seconds a frame spends per object (its passes and draws).
    pub object_seconds: f64,
    /// Seconds a frame spends per million pixels drawn (⌈√samples⌉² a picture's pixel).
    pub megapixel_seconds: f64,
}

/// Mesa's lavapipe (Vulkan), fitted (fit.py) to the whole-process times of
/// docs/measurements/2026-11-29-software/checked-groups.tsv (2026-11-30, after the CPU tracer's
/// velocity groups made the flythrough twice as fast on the CPU); the earlier collections beside
/// it are replayed against them too.
pub const LAVAPIPE: SoftwareCosts = SoftwareCosts {
    start_seconds: 0.424,
    triangle_seconds: 2.39e-6,
    object_seconds: 0.0022,
    megapixel_seconds: 0.0941,
};

/// Mesa's llvmpipe through EGL (OpenGL), fitted as [`LAVAPIPE`]: it starts in less than half
/// lavapipe's time and draws a little faster.
pub const LLVMPIPE_GL: SoftwareCosts = SoftwareCosts {
    start_seconds: 0.170,
    triangle_seconds: 2.26e-6,
    object_seconds: 0.0023,
    megapixel_seconds: 0.0803,
};

impl SoftwareCosts {
    /// The least of every cost of the software adapters measured: what no software adapter is
    /// expected to beat, for a choice made before one is opened.
    pub const CHEAPEST: Self = Self {
        start_seconds: LAVAPIPE.start_seconds.min(LLVMPIPE_GL.start_seconds),
        triangle_seconds: LAVAPIPE.triangle_seconds.min(LLVMPIPE_GL.triangle_seconds),
        object_seconds: LAVAPIPE.object_seconds.min(LLVMPIPE_GL.object_seconds),
        megapixel_seconds: LAVAPIPE
            .megapixel_seconds
            .min(LLVMPIPE_GL.megapixel_seconds),
    };

    /// The costs of a software adapter reached through `api` (lavapipe's for any but GL).
    #[must_use]
    pub const fn of(api: SoftwareApi) -> Self {
        match api {
            SoftwareApi::Gl => LLVMPIPE_GL,
            SoftwareApi::Vulkan | SoftwareApi::Other => LAVAPIPE,
        }
    }
}

/// How much of the scene a software adapter uploads and draws.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SceneSize {
    /// Triangles over every object.
    pub triangles: usize,
    /// Objects.
    pub objects: usize,
}

impl SceneSize {
    /// The size of `scene`.
    #[must_use]
    pub fn of(scene: &Scene) -> Self {
        Self {
            triangles: scene.triangle_count(),
            objects: scene.objects.len(),
        }
    }
}

/// Both estimates of what is left of a job once the CPU's cost is measured (the first frame's
/// tracer is built by then): the CPU tracer's seconds and a software adapter's.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Estimates {
    /// The CPU tracer: every later frame's tracer built and every picture traced.
    pub cpu_seconds: f64,
    /// The software adapter: its start, the upload, and every picture drawn.
    pub gpu_seconds: f64,
}

impl Estimates {
    /// The estimates of `job` on a scene of `size` from the CPU's measured `cost` and a
    /// software adapter's `costs`.
    #[must_use]
    pub fn new(job: &Job, size: SceneSize, cost: &CpuCost, costs: &SoftwareCosts) -> Self {
        let frames = f64::from(job.frames.max(1));
        let pictures = frames * f64::from(job.passes.max(1));
        let RenderSettings {
            width,
            height,
            samples,
        } = job.settings;
        let scale = f64::from(samples.max(1)).sqrt().ceil();
        let megapixels = f64::from(width) * f64::from(height) * scale * scale * 1e-6;
        Self {
            cpu_seconds: (frames - 1.0) * cost.build_seconds + pictures * cost.frame.seconds(),
            gpu_seconds: costs.start_seconds
                + costs.triangle_seconds * size.triangles as f64
                + frames * costs.object_seconds * size.objects as f64
                + pictures * costs.megapixel_seconds * megapixels,
        }
    }

    /// Whether the CPU tracer is expected to finish first (a tie goes to the CPU, whose
    /// pixels are the reference).
    #[must_use]
    pub fn cpu_is_faster(&self) -> bool {
        self.cpu_seconds <= self.gpu_seconds
    }

    /// For estimates against [`SoftwareCosts::CHEAPEST`], made before any adapter is opened:
    /// whether opening one could save more than it may waste. Rendering on the CPU without
    /// opening one loses at most `cpu_seconds − gpu_seconds`; opening one that then loses costs
    /// at least [`OPENING_SECONDS`]. The smaller of the two worst cases is taken.
    #[must_use]
    pub fn worth_opening(&self) -> bool {
        self.cpu_seconds - self.gpu_seconds > OPENING_SECONDS
    }
}

/// The estimates of `job` on a scene of `size` against a software adapter's `costs`, from the
/// CPU's `cost` measured once: where they put the adapter ahead by less than [`SECOND_LOOK`],
/// the CPU is measured again (`again`, each row keeping its shorter time) and the estimates
/// redone. A first measure that finds the CPU faster stands, as waiting on another process only
/// makes the CPU look slower. Returns the cost the estimates rest on, and the estimates.
pub fn weigh(
    job: &Job,
    size: SceneSize,
    cost: CpuCost,
    costs: &SoftwareCosts,
    again: impl FnOnce() -> CpuCost,
) -> (CpuCost, Estimates) {
    let first = Estimates::new(job, size, &cost, costs);
    if first.cpu_is_faster() || first.cpu_seconds >= SECOND_LOOK * first.gpu_seconds {
        return (cost, first);
    }
    let cost = again();
    (cost, Estimates::new(job, size, &cost, costs))
}

/// Whether this machine may have a GPU: on Linux, whether a GPU's device node exists (DRM's
/// `/dev/dri`, NVIDIA's `/dev/nvidia*`, WSL's `/dev/dxg`), through which alone a driver reaches
/// one; elsewhere always, as it cannot be told without opening an adapter. Without one, every
/// adapter wgpu could open is a software rasteriser.
#[must_use]
pub fn gpu_possible() -> bool {
    if !cfg!(target_os = "linux") {
        return true;
    }
    let dev = Path::new("/dev");
    dev.join("dri").exists()
        || dev.join("dxg").exists()
        || std::fs::read_dir(dev).map_or(true, |entries| {
            entries
                .flatten()
                .any(|entry| entry.file_name().to_string_lossy().starts_with("nvidia"))
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Five whole-process collections (collect.py and fit.py beside them): the first the
    /// constants were fitted to, a second made with them in place, a third with the CPU
    /// measured once by its threads' CPU time and its rows kept, and a fourth after the CPU
    /// tracer's velocity groups, which the present constants were fitted to, all on one AMD
    /// EPYC; a fifth on another CPU (an Intel Xeon of the same 2-core kind, 2026-12-07), with
    /// the CPU measured on at most [`srt_trace::MEASURED_SAMPLES`] samples a pixel.
    const MEASURED: [&str; 5] = [
        include_str!("../docs/measurements/2026-11-29-software/fitted.tsv"),
        include_str!("../docs/measurements/2026-11-29-software/checked.tsv"),
        include_str!("../docs/measurements/2026-11-29-software/checked-measure-once.tsv"),
        include_str!("../docs/measurements/2026-11-29-software/checked-groups.tsv"),
        include_str!("../docs/measurements/2026-12-07-intel/checked.tsv"),
    ];

    /// Two whole-process times closer than this (relative) are a tie: runs of the same
    /// command on this machine move by about as much.
    const TIE: f64 = 0.05;

    /// One measured line: the job, its scene's size, the CPU's cost as auto measured it, and
    /// the whole process's seconds on the CPU, lavapipe, llvmpipe GL and `auto` with lavapipe.
    struct Line {
        case: String,
        job: Job,
        size: SceneSize,
        cost: CpuCost,
        cpu: f64,
        vulkan: f64,
        gl: f64,
        /// `auto` with lavapipe present, and whether it rendered on the CPU.
        auto_vulkan: f64,
        auto_vulkan_chose_cpu: bool,
    }

    /// Every line of the five collections.
    fn lines() -> Vec<Line> {
        MEASURED
            .iter()
            .flat_map(|table| table_lines(table))
            .collect()
    }

    /// The lines of one collection.
    fn table_lines(table: &str) -> Vec<Line> {
        let mut rows = table.lines();
        let header: Vec<&str> = rows.next().unwrap().split('\t').collect();
        rows.map(|row| {
            let fields: Vec<&str> = row.split('\t').collect();
            let field = |name: &str| fields[header.iter().position(|h| *h == name).unwrap()];
            let number = |name: &str| field(name).parse::<f64>().unwrap();
            let whole = |name: &str| field(name).parse::<u32>().unwrap();
            let height = whole("height");
            Line {
                case: field("case").to_owned(),
                job: Job {
                    settings: RenderSettings {
                        width: whole("width"),
                        height,
                        samples: whole("samples"),
                    },
                    frames: whole("frames"),
                    passes: 1,
                },
                size: SceneSize {
                    triangles: whole("triangles") as usize,
                    objects: whole("objects") as usize,
                },
                cost: CpuCost {
                    build_seconds: number("build_s"),
                    frame: FrameCost {
                        setup_seconds: 0.0,
                        row_seconds: number("picture_s") / f64::from(height),
                        rows: height,
                    },
                },
                cpu: number("cpu"),
                vulkan: number("vulkan"),
                gl: number("gl"),
                auto_vulkan: number("auto_vulkan"),
                auto_vulkan_chose_cpu: field("auto_vulkan_chose") == "cpu",
            }
        })
        .collect()
    }

    /// The rule replayed on every measured line of the five collections, for both software
    /// adapters: it picks the faster of the CPU and the adapter, whole process against whole
    /// process, wherever they are more than a tie apart. The lines span still pictures from 640 × 360 to 3840 × 2160,
    /// 16 samples, sequences of 5 to 30 frames, 1 to 45 objects and 300 to 1.9 M triangles.
    #[test]
    fn the_rule_picks_the_faster_on_every_measured_line() {
        let lines = lines();
        assert!(lines.len() >= 30, "{} lines", lines.len());
        let mut wrong = Vec::new();
        for line in &lines {
            for (api, gpu) in [
                (SoftwareApi::Vulkan, line.vulkan),
                (SoftwareApi::Gl, line.gl),
            ] {
                let estimates =
                    Estimates::new(&line.job, line.size, &line.cost, &SoftwareCosts::of(api));
                let cpu_faster = line.cpu <= gpu;
                let tie = (line.cpu - gpu).abs() < TIE * line.cpu.min(gpu);
                if estimates.cpu_is_faster() != cpu_faster && !tie {
                    wrong.push(format!(
                        "{} on {api:?}: measured CPU {} s, GPU {gpu} s; estimated {estimates:?}",
                        line.case, line.cpu
                    ));
                }
            }
        }
        assert!(wrong.is_empty(), "{}", wrong.join("\n"));
        // Both choices occur: the lines test the rule, not a constant answer.
        let picks: Vec<bool> = lines
            .iter()
            .map(|l| Estimates::new(&l.job, l.size, &l.cost, &LAVAPIPE).cpu_is_faster())
            .collect();
        assert!(picks.contains(&true) && picks.contains(&false), "{picks:?}");
    }

    /// Where the cheapest estimates keep `auto` from opening an adapter, the CPU was measured
    /// no slower than either adapter by more than [`OPENING_SECONDS`] (or a tie), and that
    /// constant is no more than opening an adapter in vain cost where the collections made
    /// with the rule in place recorded it (`auto` that opened lavapipe and rendered on the
    /// CPU, against `--backend cpu`): on no line does leaving the adapters closed lose more
    /// than opening one would have wasted.
    #[test]
    fn an_adapter_is_left_closed_only_where_it_could_not_gain_its_opening() {
        let opened_in_vain: Vec<f64> = (MEASURED[1..].iter())
            .flat_map(|table| table_lines(table))
            .filter(|line| {
                let at_best =
                    Estimates::new(&line.job, line.size, &line.cost, &SoftwareCosts::CHEAPEST);
                !at_best.cpu_is_faster() && line.auto_vulkan_chose_cpu
            })
            .map(|line| line.auto_vulkan - line.cpu)
            .collect();
        assert!(!opened_in_vain.is_empty());
        assert!(
            opened_in_vain.iter().all(|&cost| OPENING_SECONDS <= cost),
            "opening lavapipe in vain cost {opened_in_vain:?} s"
        );
        let lines = lines();
        let mut wrong = Vec::new();
        let mut closed = 0;
        for line in &lines {
            let at_best =
                Estimates::new(&line.job, line.size, &line.cost, &SoftwareCosts::CHEAPEST);
            if at_best.worth_opening() {
                continue;
            }
            closed += 1;
            let fastest = line.vulkan.min(line.gl);
            if line.cpu > fastest + OPENING_SECONDS && line.cpu > fastest * (1.0 + TIE) {
                wrong.push(format!(
                    "{}: measured CPU {} s, lavapipe {} s, GL {} s; estimated {at_best:?}",
                    line.case, line.cpu, line.vulkan, line.gl
                ));
            }
        }
        assert!(wrong.is_empty(), "{}", wrong.join("\n"));
        // Both choices occur: the lines test the rule, not a constant answer.
        assert!(
            closed > 0 && closed < lines.len(),
            "{closed} of {}",
            lines.len()
        );
    }

    /// The cheapest costs are no adapter's more than any measured one's, cost by cost (start,
    /// triangle, object, megapixel), so that a job the CPU wins against them it wins against
    /// every software adapter: checked on the costs themselves and on every measured line's
    /// estimates.
    #[test]
    fn no_software_adapter_is_cheaper_than_the_cheapest() {
        let fields = |costs: &SoftwareCosts| {
            [
                costs.start_seconds,
                costs.triangle_seconds,
                costs.object_seconds,
                costs.megapixel_seconds,
            ]
        };
        let cheapest = fields(&SoftwareCosts::CHEAPEST);
        for costs in [LAVAPIPE, LLVMPIPE_GL] {
            for (least, cost) in cheapest.iter().zip(fields(&costs)) {
                assert!(*least <= cost, "{least} above {cost} of {costs:?}");
            }
        }
        for line in lines() {
            let at_best =
                Estimates::new(&line.job, line.size, &line.cost, &SoftwareCosts::CHEAPEST);
            for costs in [LAVAPIPE, LLVMPIPE_GL] {
                let adapter = Estimates::new(&line.job, line.size, &line.cost, &costs);
                assert!(at_best.gpu_seconds <= adapter.gpu_seconds, "{}", line.case);
                assert_eq!(at_best.cpu_seconds, adapter.cpu_seconds);
            }
        }
    }

    /// The CPU is measured a second time only where the first measure puts the adapter ahead
    /// by less than [`SECOND_LOOK`], and the estimates then rest on the second measure.
    #[test]
    fn the_cpu_is_measured_again_only_where_the_adapter_is_narrowly_ahead() {
        let line = lines()
            .into_iter()
            .find(|l| l.case == "teaser 1280x720")
            .unwrap();
        let with_picture = |seconds: f64| {
            let mut cost = line.cost;
            cost.frame.row_seconds = seconds / f64::from(cost.frame.rows);
            cost
        };
        let gpu = Estimates::new(&line.job, line.size, &line.cost, &LAVAPIPE).gpu_seconds;
        let looked_again = |first: f64, second: f64| {
            let mut asked = false;
            let (cost, estimates) =
                weigh(&line.job, line.size, with_picture(first), &LAVAPIPE, || {
                    asked = true;
                    with_picture(second)
                });
            assert_eq!(
                estimates,
                Estimates::new(&line.job, line.size, &cost, &LAVAPIPE)
            );
            (asked, estimates.cpu_is_faster())
        };
        // The CPU ahead, or the adapter far ahead: one measure.
        assert_eq!(looked_again(0.5 * gpu, 9.0), (false, true));
        assert_eq!(looked_again(1.6 * gpu, 0.1), (false, false));
        // Narrowly behind: measured again, and the second measure decides.
        assert_eq!(looked_again(1.2 * gpu, 0.9 * gpu), (true, true));
        assert_eq!(looked_again(1.2 * gpu, 1.1 * gpu), (true, false));
    }

    /// More frames, samples or pixels move a job from the CPU to a software adapter: the
    /// adapter's start is paid once, the CPU pays for every ray.
    #[test]
    fn a_larger_job_goes_to_the_software_adapter() {
        let line = lines()
            .into_iter()
            .find(|l| l.case == "teaser 1280x720")
            .unwrap();
        let at = |frames, samples: u32| {
            let mut job = line.job;
            job.frames = frames;
            job.settings.samples = samples;
            // The CPU traces every sample: its measured picture grows with them.
            let mut cost = line.cost;
            cost.frame.row_seconds *= f64::from(samples);
            Estimates::new(&job, line.size, &cost, &LAVAPIPE).cpu_is_faster()
        };
        assert!(at(1, 1));
        assert!(!at(30, 1));
        assert!(!at(1, 64));
    }
}
