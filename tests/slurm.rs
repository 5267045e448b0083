//! docs/cluster.md's Slurm job array, run as the page writes it (its `render.sh`, `join.sh` and
//! submission commands, read from the page, with tiny frames) on a one-node Slurm that the test
//! starts in a private folder (see [`Slurm`]): the joined frames must equal an unsharded run's
//! byte for byte, and a task cancelled mid-frame (`scancel`) must leave only complete frames, no
//! partial file, and be made good by submitting its share again alone.
//!
//! Where Slurm cannot start (Debian's `slurm-wlm` not installed, `slurmctld` and `slurmd` not on
//! `PATH`, or the daemons not coming up) the test prints `SKIPPED …` and passes; with
//! `SRT_REQUIRE_SLURM=1` (set by `.ci/run`) that is a failure instead.

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use crate::common::folder;

/// The programs the test runs: the two daemons and the clients the page's commands use.
const PROGRAMS: [&str; 7] = [
    "slurmctld",
    "slurmd",
    "sbatch",
    "squeue",
    "scancel",
    "scontrol",
    "sinfo",
];

/// How long the daemons may take to show the node idle, and any job to reach a state: bounds
/// against hanging for ever, far above what either takes (seconds).
const PATIENCE: Duration = Duration::from_secs(300);

/// A one-node Slurm cluster of this machine: `slurmctld` and `slurmd` in the foreground, with a
/// configuration, state, spool and logs of their own in a temporary folder, on free ports, with
/// no authentication daemon (`auth/none`) and no cgroups (it runs in containers); stopped (its
/// jobs cancelled first) when dropped, also when the test fails.
struct Slurm {
    /// The folder of the configuration, state, spool and logs.
    dir: tempfile::TempDir,
    /// The running daemons.
    daemons: Vec<Child>,
}

impl Slurm {
    /// Starts the daemons and waits until the node is idle.
    ///
    /// # Errors
    /// Why Slurm cannot run here: a program not on `PATH`, or the daemons not starting (with the
    /// end of their logs).
    fn start() -> Result<Self, String> {
        for program in PROGRAMS {
            if !on_path(program) {
                return Err(format!(
                    "{program} is not on PATH (Debian: apt install slurm-wlm)"
                ));
            }
        }
        let dir = folder();
        let user = run_text(Command::new("id").arg("-un")).map_err(|e| format!("id -un: {e}"))?;
        let cpus = std::thread::available_parallelism().map_or(1, usize::from);
        let [controller_port, node_port] = free_ports()?;
        let at = |name: &str| dir.path().join(name).display().to_string();
        for sub in ["state", "spool"] {
            std::fs::create_dir(dir.path().join(sub)).map_err(|e| e.to_string())?;
        }
        let conf = format!(
            "ClusterName=srt-test
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort={controller_port}
SlurmdPort={node_port}
SlurmUser={user}
SlurmdUser={user}
AuthType=auth/none
CredType=cred/none
MpiDefault=none
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
StateSaveLocation={state}
SlurmdSpoolDir={spool}
SlurmctldPidFile={ctld_pid}
SlurmdPidFile={d_pid}
SlurmctldLogFile={ctld_log}
SlurmdLogFile={d_log}
NodeName=localhost NodeAddr=127.0.0.1 CPUs={cpus} State=UNKNOWN
PartitionName=test Nodes=localhost Default=YES MaxTime=INFINITE State=UP
",
            state = at("state"),
            spool = at("spool"),
            ctld_pid = at("slurmctld.pid"),
            d_pid = at("slurmd.pid"),
            ctld_log = at("slurmctld.log"),
            d_log = at("slurmd.log"),
        );
        std::fs::write(dir.path().join("slurm.conf"), conf).map_err(|e| e.to_string())?;
        let mut slurm = Slurm {
            dir,
            daemons: Vec::new(),
        };
        for (daemon, args) in [
            ("slurmctld", &["-D", "-i"][..]),
            ("slurmd", &["-D", "-N", "localhost"]),
        ] {
            let log = std::fs::File::create(slurm.dir.path().join(format!("{daemon}.out")))
                .map_err(|e| e.to_string())?;
            let child = slurm
                .command(daemon)
                .args(args)
                .stdin(Stdio::null())
                .stdout(log.try_clone().map_err(|e| e.to_string())?)
                .stderr(log)
                .spawn()
                .map_err(|e| format!("{daemon} does not start: {e}"))?;
            slurm.daemons.push(child);
        }
        let deadline = Instant::now() + Duration::from_secs(60);
        loop {
            let state = run_text(slurm.command("sinfo").args(["-h", "-N", "-o", "%t"]));
            if state.as_deref() == Ok("idle") {
                return Ok(slurm);
            }
            let exited = slurm
                .daemons
                .iter_mut()
                .any(|d| !matches!(d.try_wait(), Ok(None)));
            if exited || Instant::now() > deadline {
                return Err(format!(
                    "the node is not idle ({}; sinfo: {state:?}):\n{}",
                    if exited {
                        "a daemon exited"
                    } else {
                        "after 60 s"
                    },
                    slurm.logs()
                ));
            }
            std::thread::sleep(Duration::from_millis(200));
        }
    }

    /// `program` (found on `PATH`) set up to talk to this cluster (`SLURM_CONF`), with the
    /// `srt` under test first on `PATH`, which the jobs inherit.
    fn command(&self, program: &str) -> Command {
        let srt_folder = Path::new(env!("CARGO_BIN_EXE_srt")).parent().unwrap();
        let path = std::env::var_os("PATH").unwrap_or_default();
        let paths = std::iter::once(srt_folder.to_owned()).chain(std::env::split_paths(&path));
        let mut command = Command::new(program);
        command
            .env("SLURM_CONF", self.dir.path().join("slurm.conf"))
            .env("PATH", std::env::join_paths(paths).unwrap());
        command
    }

    /// Runs the shell commands `script` with bash in `dir`, and returns their standard output.
    fn shell(&self, script: &str, dir: &Path) -> String {
        run_text(self.command("bash").args(["-euc", script]).current_dir(dir))
            .unwrap_or_else(|e| panic!("{script}\n{e}\n{}", self.logs()))
    }

    /// The `key=value` fields of job `id` (`123` or an array task `123_4`) in `scontrol`'s
    /// one-line form.
    fn job(&self, id: &str) -> String {
        run_text(self.command("scontrol").args(["show", "job", "-o", id]))
            .unwrap_or_else(|e| panic!("scontrol show job {id}: {e}"))
    }

    /// The value of `key` in job `id`'s fields (`JobState`, `Reason`).
    fn job_field(&self, id: &str, key: &str) -> String {
        let fields = self.job(id);
        field(&fields, key)
            .unwrap_or_else(|| panic!("job {id} has no {key}: {fields}"))
            .to_owned()
    }

    /// Waits until job `id`'s `key` is `value`, and fails past [`PATIENCE`] or when `JobState`
    /// settles on another final state.
    fn wait_for(&self, id: &str, key: &str, value: &str) {
        let deadline = Instant::now() + PATIENCE;
        loop {
            let fields = self.job(id);
            if field(&fields, key) == Some(value) {
                return;
            }
            let settled = !matches!(
                field(&fields, "JobState"),
                Some("PENDING" | "RUNNING" | "COMPLETING")
            );
            assert!(
                !settled && Instant::now() < deadline,
                "job {id} never had {key}={value}: {fields}\n{}",
                self.logs()
            );
            std::thread::sleep(Duration::from_millis(100));
        }
    }

    /// The daemons' logs, for failure messages.
    fn logs(&self) -> String {
        ["slurmctld.out", "slurmd.out", "slurmctld.log", "slurmd.log"]
            .iter()
            .map(|name| {
                let text = std::fs::read_to_string(self.dir.path().join(name)).unwrap_or_default();
                let tail: Vec<&str> = text.lines().rev().take(15).collect();
                let tail: Vec<&str> = tail.into_iter().rev().collect();
                format!("--- {name}:\n{}", tail.join("\n"))
            })
            .collect::<Vec<_>>()
            .join("\n")
    }
}

impl Drop for Slurm {
    /// Cancels every job (a job's processes outlive `slurmd`), waits for them to end, then stops
    /// the daemons (SIGTERM, and SIGKILL if they do not end within a minute).
    fn drop(&mut self) {
        if let Ok(user) = run_text(Command::new("id").arg("-un")) {
            let _ = self.command("scancel").args(["-u", &user]).status();
            let deadline = Instant::now() + Duration::from_secs(60);
            while run_text(
                self.command("squeue")
                    .args(["-h", "-t", "RUNNING,COMPLETING"]),
            )
            .is_ok_and(|jobs| !jobs.is_empty())
                && Instant::now() < deadline
            {
                std::thread::sleep(Duration::from_millis(100));
            }
        }
        for daemon in self.daemons.iter_mut().rev() {
            let _ = Command::new("kill")
                .args(["-s", "TERM", &daemon.id().to_string()])
                .status();
            let deadline = Instant::now() + Duration::from_secs(60);
            while matches!(daemon.try_wait(), Ok(None)) && Instant::now() < deadline {
                std::thread::sleep(Duration::from_millis(50));
            }
            let _ = daemon.kill();
            let _ = daemon.wait();
        }
    }
}

/// The value of `key` in `fields`, `scontrol`'s `key=value` words.
fn field<'f>(fields: &'f str, key: &str) -> Option<&'f str> {
    (fields.split_whitespace()).find_map(|word| word.strip_prefix(key)?.strip_prefix('='))
}

/// Whether `program` is an executable file in a folder of `PATH`.
fn on_path(program: &str) -> bool {
    let path = std::env::var_os("PATH").unwrap_or_default();
    std::env::split_paths(&path).any(|folder| {
        use std::os::unix::fs::PermissionsExt as _;
        std::fs::metadata(folder.join(program))
            .is_ok_and(|m| m.is_file() && m.permissions().mode() & 0o111 != 0)
    })
}

/// Two distinct TCP ports on 127.0.0.1 that were free a moment ago.
fn free_ports() -> Result<[u16; 2], String> {
    let bind = || std::net::TcpListener::bind("127.0.0.1:0").map_err(|e| e.to_string());
    let port = |listener: &std::net::TcpListener| match listener.local_addr() {
        Ok(address) => Ok(address.port()),
        Err(error) => Err(error.to_string()),
    };
    let listeners = [bind()?, bind()?];
    Ok([port(&listeners[0])?, port(&listeners[1])?])
}

/// Runs `command` and returns its standard output, trimmed; an error with its standard error
/// when it fails.
fn run_text(command: &mut Command) -> Result<String, String> {
    let output = command.output().map_err(|e| format!("{command:?}: {e}"))?;
    if !output.status.success() {
        return Err(format!(
            "{command:?}: {}\n{}",
            output.status,
            String::from_utf8_lossy(&output.stderr)
        ));
    }
    Ok(String::from_utf8_lossy(&output.stdout).trim().to_owned())
}

/// A started [`Slurm`], or `None` after a visible skip line where it cannot start; a failure
/// instead when `SRT_REQUIRE_SLURM=1`.
fn slurm_or_skip(test: &str) -> Option<Slurm> {
    match Slurm::start() {
        Ok(slurm) => Some(slurm),
        Err(why) => {
            assert!(
                std::env::var("SRT_REQUIRE_SLURM").as_deref() != Ok("1"),
                "{test}: SRT_REQUIRE_SLURM=1 but Slurm cannot start here: {why}"
            );
            // Written to stderr directly: the test harness captures `eprintln!` of passing
            // tests, and a skip must be visible.
            let _ = writeln!(
                std::io::stderr(),
                "SKIPPED {test}: Slurm cannot start here ({why}); set SRT_REQUIRE_SLURM=1 to make this a failure"
            );
            None
        }
    }
}

/// The code blocks of docs/cluster.md's section "Slurm job array", in order: `render.sh`,
/// `join.sh` and the submission commands.
fn documented_scripts() -> [String; 3] {
    let page = include_str!("../docs/cluster.md");
    let section = page
        .split("\n### ")
        .find(|s| s.starts_with("Slurm job array\n"))
        .expect("docs/cluster.md has a section \"Slurm job array\"");
    let blocks: Vec<String> = section
        .split("```sh\n")
        .skip(1)
        .map(|rest| rest.split("```").next().unwrap().to_owned())
        .collect();
    let blocks: [String; 3] = blocks
        .try_into()
        .expect("the section shows render.sh, join.sh and the commands that submit them");
    for (block, name) in blocks.iter().zip(["render.sh", "join.sh"]) {
        assert!(
            block.starts_with(&format!("#!/bin/bash\n# {name}\n")),
            "a block names itself {name} on its second line:\n{block}"
        );
    }
    blocks
}

/// `text` with its one occurrence of `documented` replaced by `tiny`.
fn replace_once(text: &str, documented: &str, tiny: &str) -> String {
    assert_eq!(
        text.matches(documented).count(),
        1,
        "docs/cluster.md's script has not exactly one {documented:?}:\n{text}"
    );
    text.replace(documented, tiny)
}

/// The names of the files in `dir`, sorted.
fn file_names(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|entry| entry.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// The processes (their `/proc` folders) of task `task` of array job `array`: those with the
/// environment Slurm gave the task.
fn task_processes(array: &str, task: u32) -> Vec<PathBuf> {
    let wanted = [
        format!("SLURM_ARRAY_JOB_ID={array}"),
        format!("SLURM_ARRAY_TASK_ID={task}"),
    ];
    let Ok(processes) = std::fs::read_dir("/proc") else {
        return Vec::new();
    };
    (processes.flatten())
        .map(|process| process.path())
        .filter(|process| {
            std::fs::read(process.join("environ")).is_ok_and(|environment| {
                let variables: Vec<&[u8]> = environment.split(|&byte| byte == 0).collect();
                wanted.iter().all(|v| variables.contains(&v.as_bytes()))
            })
        })
        .collect()
}

/// A process of task `task` of array job `array` that holds a partial file (`.srt-….partial`,
/// an unfinished frame) open, if any: its `/proc` folder and the file.
fn partial_file_of(array: &str, task: u32) -> Option<(PathBuf, PathBuf)> {
    task_processes(array, task).into_iter().find_map(|process| {
        let open = std::fs::read_dir(process.join("fd")).ok()?;
        let partial = open.flatten().find_map(|fd| {
            let file = std::fs::read_link(fd.path()).ok()?;
            let name = file.file_name()?.to_string_lossy().into_owned();
            (name.starts_with(".srt-") && name.ends_with(".partial")).then_some(file)
        })?;
        Some((process, partial))
    })
}

/// Sends `signal` (`STOP`, `CONT`) to the process of `/proc` folder `process`.
fn signal(process: &Path, signal: &str) {
    let pid = process.file_name().unwrap().to_string_lossy().into_owned();
    // The process may have ended since it was seen: then there is nothing to signal.
    let _ = Command::new("kill").args(["-s", signal, &pid]).status();
}

/// What job `id` (`123`, or an array task `123_4`) printed: Slurm's `slurm-ID.out` in the
/// folder it was submitted from (empty before it starts).
fn job_output(dir: &Path, id: &str) -> String {
    std::fs::read_to_string(dir.join(format!("slurm-{id}.out"))).unwrap_or_default()
}

/// The number of frame `name` (`f_0012.png` → 12).
fn frame_number(name: &str) -> Option<usize> {
    name.strip_prefix("f_")?.strip_suffix(".png")?.parse().ok()
}

/// The documented array, two shares of 8 frames, with its join. Share 1 is cancelled in the
/// middle of its second frame or a later one: it leaves complete frames and no partial file,
/// and the join waits for ever. As the page says, that share is submitted again
/// alone and the join after it. Then every frame, those written before the cancel too, is the
/// unsharded run's of the same command byte for byte, and so is the joined video.
#[test]
fn the_documented_job_array_renders_the_frames_of_one_run_and_survives_a_cancelled_task() {
    let test = "slurm::the_documented_job_array_renders_the_frames_of_one_run_and_survives_a_cancelled_task";
    let Some(slurm) = slurm_or_skip(test) else {
        return;
    };
    let [render, join, submit] = documented_scripts();
    // Small frames: 8 of 160x90, in two shares.
    let render = [
        ("--array=1-32", "--array=1-2"),
        ("--cpus-per-task=16", "--cpus-per-task=1"),
        (
            "\"${SLURM_ARRAY_TASK_ID}/32\"",
            "\"${SLURM_ARRAY_TASK_ID}/2\"",
        ),
        (
            "--samples 16 --width 1920 --height 1080",
            "--samples 64 --width 160 --height 90",
        ),
        ("--frames 2400", "--frames 8"),
        // The objects stay in view (frames of about equal cost).
        ("--t0 0 --t1 100", "--t0 0 --t1 4"),
    ]
    .iter()
    .fold(render, |text, (documented, tiny)| {
        replace_once(&text, documented, tiny)
    });
    let frames = 8;

    let [cluster, unsharded] = [folder(), folder()];
    for dir in [&cluster, &unsharded] {
        std::fs::write(
            dir.path().join("flight.toml"),
            include_str!("../crates/srt-scene/assets/scenes/teaser.toml"),
        )
        .unwrap();
        std::fs::write(dir.path().join("render.sh"), &render).unwrap();
        std::fs::write(dir.path().join("join.sh"), &join).unwrap();
    }
    let dir = cluster.path();
    let frames_dir = dir.join("frames");

    // The node does not bind a task to the one CPU it asks for (no cgroups here): each is held
    // to one thread, as a cluster's binding would, so that a frame takes long enough (tenths of
    // a second) to be seen unfinished on a machine of many cores too.
    let one_thread = "export RAYON_NUM_THREADS=1";
    // The page's commands, then the array's id they keep.
    let said = slurm.shell(
        &format!("{one_thread}\n{submit}\necho \"array=$array\""),
        dir,
    );
    let array = said
        .lines()
        .find_map(|line| line.strip_prefix("array="))
        .unwrap_or_else(|| panic!("no array id:\n{said}"))
        .to_owned();
    let first_join = said
        .lines()
        .find_map(|line| line.strip_prefix("Submitted batch job "))
        .unwrap_or_else(|| panic!("the join was not submitted:\n{said}"))
        .to_owned();

    // Share 1 writes frames 0, 2, 4, …: once frame 0 is there, its srt is stopped (SIGSTOP)
    // while it holds the partial file of a later frame open, so that the cancel lands in that
    // frame whatever the machine's speed. Slurm's cancel sends SIGCONT, then SIGTERM.
    let share_1 = format!("{array}_1");
    let first_frame = frames_dir.join("f_0000.png");
    let deadline = Instant::now() + PATIENCE;
    let mut state_seen = Instant::now();
    let partial = loop {
        if first_frame.exists()
            && let Some((process, _)) = partial_file_of(&array, 1)
        {
            signal(&process, "STOP");
            // Stopped, it cannot finish the frame: if it still holds a partial file, that frame
            // is unfinished.
            match partial_file_of(&array, 1) {
                Some((_, partial)) => break partial,
                None => signal(&process, "CONT"),
            }
        }
        // The files are looked at every millisecond; Slurm, slower to ask, every two seconds
        // until the first frame is there, then the task's processes.
        if first_frame.exists() {
            assert!(
                !task_processes(&array, 1).is_empty(),
                "share 1 ended before it was seen writing a second frame:\n{}",
                job_output(dir, &share_1)
            );
        } else if state_seen.elapsed() > Duration::from_secs(2) {
            let state = slurm.job_field(&share_1, "JobState");
            assert!(
                matches!(state.as_str(), "PENDING" | "RUNNING") && Instant::now() < deadline,
                "share 1 ({state}) wrote no frame:\n{}\n{}",
                job_output(dir, &share_1),
                slurm.logs()
            );
            state_seen = Instant::now();
        }
        std::thread::sleep(Duration::from_millis(1));
    };
    slurm.shell(&format!("scancel {share_1}"), dir);
    slurm.wait_for(&share_1, "JobState", "CANCELLED");
    // Slurm may say so before the task's processes have ended.
    let deadline = Instant::now() + PATIENCE;
    while !task_processes(&array, 1).is_empty() {
        assert!(Instant::now() < deadline, "share 1's processes never end");
        std::thread::sleep(Duration::from_millis(10));
    }
    let said = job_output(dir, &share_1);
    assert!(
        said.contains("interrupted: removed 1 unfinished output file(s)"),
        "share 1 was not cancelled mid-frame, or did not clean up:\n{said}"
    );
    assert!(!partial.exists(), "{} is left", partial.display());

    // Share 2 goes on; the join waits for ever on the cancelled share, as the page says.
    slurm.wait_for(&format!("{array}_2"), "JobState", "COMPLETED");
    slurm.wait_for(&first_join, "Reason", "DependencyNeverSatisfied");
    assert_eq!(slurm.job_field(&first_join, "JobState"), "PENDING");
    let cancelled = file_names(&frames_dir);
    assert!(
        !cancelled.iter().any(|name| name.ends_with(".partial")),
        "a partial file after the cancel: {cancelled:?}"
    );
    let of_share_1: Vec<&String> = (cancelled.iter())
        .filter(|name| frame_number(name).is_some_and(|i| i % 2 == 0))
        .collect();
    assert!(
        !of_share_1.is_empty() && of_share_1.len() < frames / 2,
        "the cancelled share 1 has frames {of_share_1:?} of {}",
        frames / 2
    );
    // Kept to compare with the unsharded run's, byte for byte: the rerun overwrites them.
    let before_rerun: Vec<(String, Vec<u8>)> = (cancelled.iter())
        .map(|name| (name.clone(), std::fs::read(frames_dir.join(name)).unwrap()))
        .collect();

    // Share 1 again alone, and the join after it.
    slurm.shell(&format!("scancel {first_join}"), dir);
    let again = slurm.shell(
        &format!("{one_thread}\nsbatch --parsable --array=1 render.sh"),
        dir,
    );
    let join_again = slurm.shell(
        &format!("sbatch --parsable --dependency=afterok:{again} join.sh"),
        dir,
    );
    slurm.wait_for(&format!("{again}_1"), "JobState", "COMPLETED");
    let said = job_output(dir, &format!("{again}_1"));
    let wrote: Vec<&str> = (said.lines())
        .filter_map(|line| line.strip_prefix("wrote frames/")?.split(' ').next())
        .collect();
    assert_eq!(
        wrote,
        ["f_0000.png", "f_0002.png", "f_0004.png", "f_0006.png"],
        "share 1 submitted alone renders its own frames:\n{said}"
    );
    slurm.wait_for(&join_again, "JobState", "COMPLETED");
    let joined = job_output(dir, &join_again);
    assert!(
        joined.contains(&format!(
            "wrote flight.mp4 ({frames} frames, 160x90, 24 fps"
        )),
        "{joined}"
    );

    // The same command without --shard, then join.sh, outside Slurm.
    let one_run = replace_once(
        render
            .lines()
            .filter(|l| !l.starts_with('#'))
            .collect::<Vec<_>>()
            .join("\n")
            .as_str(),
        " \\\n    --shard \"${SLURM_ARRAY_TASK_ID}/2\"",
        "",
    );
    slurm.shell(
        &format!("mkdir frames\n{one_run}\nbash join.sh"),
        unsharded.path(),
    );
    let expected = file_names(&unsharded.path().join("frames"));
    assert_eq!(expected.len(), frames, "{expected:?}");
    assert_eq!(file_names(&frames_dir), expected);
    for name in &expected {
        let read = |dir: &Path| std::fs::read(dir.join("frames").join(name)).unwrap();
        assert!(
            read(dir) == read(unsharded.path()),
            "{name} differs from the unsharded run's"
        );
    }
    for (name, bytes) in &before_rerun {
        let expected = std::fs::read(unsharded.path().join("frames").join(name)).unwrap();
        assert!(
            *bytes == expected,
            "{name}, written before the cancel, differs from the unsharded run's"
        );
    }
    let read = |dir: &Path| std::fs::read(dir.join("flight.mp4")).unwrap();
    assert!(
        read(dir) == read(unsharded.path()),
        "the joined video differs from the unsharded run's"
    );
}
