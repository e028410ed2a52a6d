//! The command line's promises (docs/reliability.md): exit codes, signals, closed pipes,
//! full disks, resume flags and checkpoint paths that would overwrite the user's work.

use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::time::Duration;

fn noncirc() -> Command {
    Command::new(env!("CARGO_BIN_EXE_noncirc"))
}

fn temp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("noncirc-cli-{}-{name}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A search that runs until it is stopped, checkpointing to `checkpoint`.
fn long_search(checkpoint: &std::path::Path) -> Command {
    let mut search = noncirc();
    search
        .args([
            "optimise",
            "--budget",
            "100000000",
            "--quiet",
            "--checkpoint",
        ])
        .arg(checkpoint);
    search
}

/// Waits until `what` holds: a guard against a hang (60 s), not a timing claim.
fn wait_until(mut what: impl FnMut() -> bool) {
    for _ in 0..600 {
        if what() {
            return;
        }
        std::thread::sleep(Duration::from_millis(100));
    }
    panic!("waited 60 s");
}

/// Sends SIGINT to `child`, as Ctrl-C does.
fn interrupt(child: &std::process::Child) {
    assert!(Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap()
        .success());
}

/// Runs `noncirc COMMAND ARGS --out OUT` and asserts that it is refused as bad input:
/// exit 2, `says` in its message, nothing written at `out`.
fn assert_refused<S: AsRef<std::ffi::OsStr> + std::fmt::Debug>(
    command: &str,
    args: &[S],
    says: &str,
    out: &std::path::Path,
) {
    let run = noncirc()
        .arg(command)
        .args(args)
        .arg("--out")
        .arg(out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{args:?}: {stderr}");
    assert!(stderr.contains(says), "{args:?}: {stderr}");
    assert!(!out.exists(), "{args:?}: wrote {}", out.display());
}

#[test]
fn exit_codes_tell_bad_input_from_runtime_failure() {
    let code = |args: &[&str]| noncirc().args(args).output().unwrap().status.code();
    assert_eq!(code(&["evaluate"]), Some(0));
    assert_eq!(
        code(&["evaluate", "--set", "bounds.module_min_mm=nan"]),
        Some(2)
    );
    assert_eq!(code(&["optimise", "--threads", "2000"]), Some(2));
    assert_eq!(
        code(&["optimise", "--population", "9223372036854775807"]),
        Some(2)
    );
    assert_eq!(code(&["optimise", "--checkpoint-every", "inf"]), Some(2));
    assert_eq!(code(&["evaluate", "no-such-file.toml"]), Some(2));
    assert_eq!(
        code(&["optimise", "--resume", "no-such-checkpoint.json"]),
        Some(2)
    );
    // A runtime failure: the output directory cannot be created under a file.
    let dir = temp("runtime");
    let file = dir.join("file");
    std::fs::write(&file, "x").unwrap();
    let plot = file.join("figures");
    assert_eq!(
        code(&["evaluate", "--plot", plot.to_str().unwrap()]),
        Some(1)
    );
}

#[test]
fn sigterm_stops_a_search_with_its_results_and_exit_130() {
    let dir = temp("sigterm");
    let (cp, out) = (dir.join("run.ckpt"), dir.join("out"));
    let child = long_search(&cp)
        .arg("--out")
        .arg(&out)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(1500));
    let pid = child.id().to_string();
    assert!(Command::new("kill")
        .args(["-TERM", &pid])
        .status()
        .unwrap()
        .success());
    let output = child.wait_with_output().unwrap();
    assert_eq!(output.status.code(), Some(130), "{output:?}");
    assert!(String::from_utf8_lossy(&output.stdout).contains("evaluations"));
    assert!(out.join("best.toml").exists());
    // It stopped on the signal, not at the budget's end (counted, not timed).
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["stopped_early"], true, "{summary}");
    assert!(
        summary["evaluations"].as_u64().unwrap() < 100_000_000,
        "{summary}"
    );
    // The checkpoint resumes.
    assert_resumes(&cp, "1");
    std::fs::remove_dir_all(dir).ok();
}

/// A search whose first generation alone runs for minutes: 20 000 designs at 30 000
/// samples a turn on one thread (about 3.6 ms each).
fn one_long_generation(checkpoint: &std::path::Path) -> std::process::Child {
    noncirc()
        .args([
            "optimise",
            "--quiet",
            "--threads",
            "1",
            "--population",
            "20000",
        ])
        .args([
            "--set",
            "search.screening.samples_per_turn=30000",
            "--checkpoint",
        ])
        .arg(checkpoint)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap()
}

#[test]
fn a_signal_inside_a_generation_stops_it_and_a_second_signal_ends_at_once() {
    let dir = temp("mid-generation");
    let cp = dir.join("run.ckpt");
    // The checkpoint is written before the first evaluation: the generation has begun.
    let child = one_long_generation(&cp);
    wait_until(|| cp.exists());
    std::thread::sleep(Duration::from_millis(300));
    interrupt(&child);
    let output = child.wait_with_output().unwrap();
    assert_eq!(output.status.code(), Some(130), "{output:?}");
    // Stopped inside the first generation (counted, not timed): had it waited for the
    // generation's end, 20 000 evaluations would be kept. The generation in flight is
    // dropped; the kept state is the last complete one, here the start, and resumes.
    let state: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&cp).unwrap()).unwrap();
    assert_eq!(state["state"]["evaluations"], 0, "{}", state["state"]);
    assert_eq!(state["state"]["generation"], 0);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(stdout.contains("NO DESIGN EVALUATED"), "{stdout}");

    // A signal stops the search, then its figures are drawn (in PNG and PDF, hundreds of
    // milliseconds); a second signal meanwhile ends the process at once. Signals are sent
    // until it ends: two sent together would merge into one.
    let (cp, plots) = (dir.join("second.ckpt"), dir.join("plots"));
    let mut child = long_search(&cp)
        .arg("--plot")
        .arg(&plots)
        .args(["--figure-format", "png,pdf"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    wait_until(|| cp.exists());
    wait_until(|| {
        interrupt(&child);
        std::thread::sleep(Duration::from_millis(10));
        child.try_wait().unwrap().is_some()
    });
    let output = child.wait_with_output().unwrap();
    assert_eq!(output.status.code(), Some(130), "{output:?}");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("second signal"), "{stderr}");
    std::fs::remove_dir_all(dir).ok();
}

/// Resumes the checkpoint `cp` with a budget of `budget` and asserts that it succeeds.
fn assert_resumes(cp: &std::path::Path, budget: &str) {
    let resumed = noncirc()
        .args(["optimise", "--quiet", "--budget", budget, "--resume"])
        .arg(cp)
        .output()
        .unwrap();
    assert_eq!(resumed.status.code(), Some(0), "{resumed:?}");
}

#[test]
fn a_closed_pipe_ends_quietly_and_a_full_disk_says_so() {
    let mut child = noncirc()
        .args([
            "sweep",
            "--param",
            "train.phi0_deg",
            "--from",
            "-80",
            "--to",
            "-40",
        ])
        .args(["--steps", "2000", "--format", "json"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Read one byte, then close the pipe (as `| head -c1` does).
    {
        use std::io::Read;
        let mut stdout = child.stdout.take().unwrap();
        let mut byte = [0u8; 1];
        stdout.read_exact(&mut byte).unwrap();
    }
    let output = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(output.status.code(), Some(0), "{stderr}");
    if std::path::Path::new("/dev/full").exists() {
        let full = std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .unwrap();
        let output = noncirc().arg("evaluate").stdout(full).output().unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(1), "{stderr}");
        assert!(
            stderr.contains("cannot write to standard output"),
            "{stderr}"
        );
        // A standard error that cannot be written loses the message, not the exit code
        // (a panic gave 101).
        let full = std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .unwrap();
        let output = noncirc()
            .args(["evaluate", "--set", "train.phi0_deg=nan"])
            .stderr(full)
            .output()
            .unwrap();
        assert_eq!(output.status.code(), Some(2));
    }
    // An interrupted search whose reader went away still says it was interrupted (130).
    let dir = temp("gone-reader");
    let cp = dir.join("run.json");
    let mut child = long_search(&cp)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    // The first checkpoint comes after the signal handler.
    wait_until(|| cp.exists());
    interrupt(&child);
    assert_eq!(child.wait().unwrap().code(), Some(130));
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn a_resume_refuses_flags_it_would_ignore() {
    let dir = temp("resume");
    let cp = dir.join("run.ckpt");
    let first = noncirc()
        .args(["optimise", "--quiet", "--budget", "500", "--checkpoint"])
        .arg(&cp)
        .output()
        .unwrap();
    assert!(first.status.success(), "{first:?}");
    for flags in [
        &["--seed", "3"][..],
        &["--algorithm", "cmaes"],
        &["--population", "10"],
        &["--set", "search.seed=4"],
        &["paper-search"],
    ] {
        let output = noncirc()
            .args(["optimise", "--quiet", "--resume"])
            .arg(&cp)
            .args(flags)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{flags:?}: {stderr}");
        assert!(stderr.contains("would be ignored"), "{stderr}");
    }
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn a_checkpoint_never_overwrites_another_file() {
    let dir = temp("overwrite");
    let scene = dir.join("ps.toml");
    let text = include_str!("../../../scenes/paper-search.toml");
    std::fs::write(&scene, text).unwrap();
    let output = noncirc()
        .args(["optimise", "--quiet", "--budget", "200"])
        .arg(&scene)
        .arg("--checkpoint")
        .arg(&scene)
        .output()
        .unwrap();
    assert!(!output.status.success());
    assert!(String::from_utf8_lossy(&output.stderr).contains("refusing to overwrite"));
    assert_eq!(std::fs::read_to_string(&scene).unwrap(), text);
    // Nor does a temporary file stay behind after a normal run.
    let cp = dir.join("run.ckpt");
    let ok = noncirc()
        .args(["optimise", "--quiet", "--budget", "200", "--checkpoint"])
        .arg(&cp)
        .output()
        .unwrap();
    assert!(ok.status.success(), "{ok:?}");
    let names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names.len(), 2, "{names:?}");
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn teeth_reports_its_checks_and_names_what_it_refuses() {
    // The largest undercut-free module's 18 teeth, and the undercut the rule misses: the
    // verdict fails (exit 3), the report is printed with the settings tried, and the
    // export is refused unless forced.
    let dir = temp("teeth-verdict");
    let export = dir.join("out");
    let out = noncirc()
        .args(["teeth", "ellipse-gear", "--format", "json", "--export"])
        .arg(&export)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(3));
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("\"teeth\": 18"), "{text}");
    assert!(text.contains("\"undercut_teeth\": 4"), "{text}");
    assert!(text.contains("\"advice\""), "{text}");
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(
        err.contains("not exported") && err.contains("--force"),
        "{err}"
    );
    assert!(!export.exists());
    let forced = noncirc()
        .args(["teeth", "ellipse-gear", "--force", "--export"])
        .arg(&export)
        .output()
        .unwrap();
    assert_eq!(forced.status.code(), Some(3));
    assert!(export.join("driver.dxf").exists());
    // Allowed undercut: every check passes, exit 0.
    let passes = noncirc()
        .args([
            "teeth",
            "ellipse-gear",
            "--set",
            "gear.teeth.allow_undercut=true",
        ])
        .output()
        .unwrap();
    assert_eq!(passes.status.code(), Some(0));
    for (args, named) in [
        (
            &["--set", "gear.teeth.pressure_angle_deg=60"][..],
            "gear.teeth.pressure_angle_deg",
        ),
        (&["--tolerance-mm", "0"][..], "--tolerance-mm"),
        (&["--tolerance-mm", "1e-300"][..], "from 1e-6 to 0.05"),
        // A gear scene assembles no train, yet a NaN angle is refused, not ignored.
        (&["--carrier-deg", "nan"][..], "--carrier-deg"),
        (&["--set", "gear.module.teeth=2"][..], "gear.module.teeth"),
        (
            &["--set", "gear.teeth.cutter={kind=\"shaper\",teeth=20}"][..],
            "20-tooth shaper",
        ),
    ] {
        let out = noncirc()
            .args(["teeth", "ellipse-gear"])
            .args(args)
            .output()
            .unwrap();
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(named), "{args:?}: {err}");
    }
    // The paper's curve: a concave arc of 1.9 mm that no cutter can cut at module 2.5,
    // named with its tooth; the verdict's exit code.
    let out = noncirc()
        .args(["teeth", "paper", "--set", "gear.module.teeth=40"])
        .output()
        .unwrap();
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(out.status.code(), Some(3), "{err}");
    assert!(
        err.contains("a rack cannot cut a concave arc")
            && err.contains("no shaper")
            && err.contains("tooth 23 "),
        "{err}"
    );
    // As JSON: the refusal and the settings tried, for a script.
    let out = noncirc()
        .args([
            "teeth",
            "paper",
            "--set",
            "gear.module.teeth=40",
            "--format",
            "json",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(3));
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(report["refused"].as_str().unwrap().contains("tooth 23 "));
    assert!(!report["advice"]["tried"].as_array().unwrap().is_empty());
}

#[test]
fn robustness_and_sensitivity_report_and_name_what_they_refuse() {
    let run = |args: &[&str]| noncirc().args(args).output().unwrap();
    // The paper's design misses its module bound: no built machine meets every objective,
    // and the table says so with the worst case of each objective.
    let ok = run(&["robustness", "--samples", "32"]);
    assert_eq!(ok.status.code(), Some(0));
    let table = String::from_utf8(ok.stdout).unwrap();
    assert!(table.contains("P(every objective met) = 0.0000"), "{table}");
    assert!(
        table.contains("module") && table.contains("at corner"),
        "{table}"
    );
    let json = run(&["robustness", "--samples", "16", "--format", "json"]);
    let v: serde_json::Value = serde_json::from_slice(&json.stdout).unwrap();
    assert_eq!(v["samples"], 16);
    assert_eq!(v["objectives"].as_array().unwrap().len(), 9);
    for (args, named) in [
        (&["robustness", "--samples", "0"][..], "tolerances.samples"),
        (
            &["robustness", "--set", "tolerances.beta0_deg={sigma=-1}"][..],
            "tolerances.beta0_deg.sigma",
        ),
        (
            &["sensitivity", "--box-scale", "2"][..],
            "box_scale) = 2.0: expected",
        ),
        (&["sensitivity", "--base-samples", "1"][..], "base samples"),
        (
            &[
                "optimise",
                "--set",
                "search.goals=[\"margin_quantile:1.5\"]",
            ][..],
            "margin_quantile:1.5",
        ),
    ] {
        let out = run(args);
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(named), "{args:?}: {err}");
    }
}

#[test]
fn compare_reports_both_arm_counts_and_names_what_it_refuses() {
    let run = |args: &[&str]| noncirc().args(args).output().unwrap();
    let dir = temp("compare");
    let plot = dir.to_str().unwrap();
    let ok = run(&[
        "compare", "--seeds", "1", "--budget", "20000", "--format", "json", "--plot", plot,
    ]);
    assert_eq!(
        ok.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&ok.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&ok.stdout).unwrap();
    assert_eq!(v["measure"], "in_tray_speed_m_s");
    assert_eq!(v["arms"].as_array().unwrap().len(), 2);
    assert_eq!(v["reductions"][0]["arms"], 3);
    for file in [
        "speed_comparison.png",
        "arms_2/best.toml",
        "arms_3/trajectory.png",
    ] {
        assert!(dir.join(file).is_file(), "{file}");
    }
    // The scene written for two arms is the design the table reports, with its arm count.
    let best = dir.join("arms_2/best.toml");
    let eval = run(&["evaluate", best.to_str().unwrap(), "--format", "json"]);
    let e: serde_json::Value = serde_json::from_slice(&eval.stdout).unwrap();
    assert_eq!(e["events"]["arms"].as_array().unwrap().len(), 2);
    for (args, named) in [
        (&["compare", "--arms", "2,5"][..], "train.arms = 5"),
        (
            &["compare", "--measure", "loop_height_mm"][..],
            "loop_height_mm",
        ),
        (&["compare", "--measure", "nope"][..], "nope"),
        (
            &["compare", "--picks-per-minute", "0"][..],
            "picks per minute = 0",
        ),
        (&["compare", "--seeds", ""][..], "seed"),
    ] {
        let out = run(args);
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(named), "{args:?}: {err}");
    }
}

#[test]
fn fit_refuses_bad_targets_by_name_with_exit_2_and_writes_nothing() {
    let dir = temp("fit-targets");
    let circle = |n: usize, r: f64, keep: usize| -> String {
        (0..keep)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / n as f64;
                format!("{},{}\n", r * a.cos(), r * a.sin() - 100.0)
            })
            .collect()
    };
    let cases: [(&str, String, &str); 6] = [
        (
            "open.csv",
            circle(40, 150.0, 30),
            "target.x_mm[29]: the target path is open",
        ),
        (
            "few.csv",
            "0,0\n10,0\n10,10\n".into(),
            "needs at least 4 points, got 3",
        ),
        (
            "nan.csv",
            circle(40, 150.0, 40).replacen("150,", "NaN,", 1),
            "target.x_mm[0] must be a finite number",
        ),
        (
            "crossing.csv",
            "0,0\n100,100\n100,0\n0,100\n".into(),
            "the target path crosses itself at (50.000, 50.000) mm",
        ),
        // In tenths of a millimetre: 1.5 m from the carrier axis.
        ("far.csv", circle(40, 1500.0, 40), "out of the arm's reach"),
        (
            "words.csv",
            "x_mm,y_mm\n1,2\nthree,4\n".into(),
            "line 3: expected two numbers",
        ),
    ];
    for (name, text, says) in cases {
        let file = dir.join(name);
        std::fs::write(&file, text).unwrap();
        let args = [
            std::ffi::OsStr::new("--quiet"),
            "--target".as_ref(),
            file.as_os_str(),
        ];
        assert_refused("fit", &args, says, &dir.join(format!("out-{name}")));
    }
    // No target at all.
    let run = noncirc().args(["fit", "--quiet"]).output().unwrap();
    assert_eq!(run.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&run.stderr).contains("a fit needs a target"));
}

/// `noncirc inverse` on the two drawn targets (scenes/targets/): the peach is blocked, and
/// the inversion names each blocking condition with its arc; the loop is built, written as
/// a scene the other commands read, and its failures (concave pitch curves, the module)
/// are named. Both exit 3 with their outputs written.
#[test]
fn inverse_names_what_blocks_a_drawn_target_and_writes_what_it_builds() {
    let targets = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/targets");
    let dir = temp("inverse-drawn");
    let run = |name: &str, exit: i32| {
        let out = dir.join(name);
        let run = noncirc()
            .args(["inverse", "--format", "json", "--target"])
            .arg(format!("{targets}/{name}.toml"))
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        assert_eq!(
            run.status.code(),
            Some(exit),
            "{name}: {}",
            String::from_utf8_lossy(&run.stderr)
        );
        let json: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
        let written: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("inverse.json")).unwrap())
                .unwrap();
        assert_eq!(json, written, "{name}: inverse.json is what was printed");
        (json, out)
    };
    let failing = |json: &serde_json::Value| -> Vec<(String, bool, usize)> {
        (json["conditions"].as_array().unwrap().iter())
            .filter(|c| c["holds"] == false)
            .map(|c| {
                let name = c["name"].as_str().unwrap().to_string();
                (
                    name,
                    c["blocks"] == true,
                    c["places"].as_array().unwrap().len(),
                )
            })
            .collect()
    };
    let (peach, out) = run("drawn-peach", 3);
    assert_eq!(peach["built"], false);
    assert!(!out.join("inverse.toml").exists());
    let blocked = failing(&peach);
    for name in ["carrier_advances", "ratio_positive"] {
        let c = blocked.iter().find(|c| c.0 == name).expect(name);
        assert!(c.1 && c.2 > 0, "{name} blocks and says where: {c:?}");
    }
    // The drawn loop inverts to a train that meets every condition and all nine
    // objectives (its ratio shaped within the tolerance's budget: 0.9 τ less the series').
    let (lp, out) = run("drawn-loop", 0);
    assert_eq!(
        (lp["built"].clone(), lp["met"].clone()),
        (true.into(), true.into())
    );
    let tolerance = 2.0;
    assert!(
        lp["path_hausdorff_mm"].as_f64().unwrap() <= tolerance,
        "{lp}"
    );
    let shaped = lp["shaping_mm"].as_f64().unwrap();
    let smoothing = lp["smoothing_mm"].as_f64().unwrap();
    assert!(
        shaped > 0.0 && shaped <= 0.9 * tolerance - smoothing,
        "{lp}"
    );
    assert!(failing(&lp).is_empty(), "{:?}", failing(&lp));
    // The written design is a scene like any other: evaluate reads it, and finds its
    // path on the target within the tolerance.
    let run = noncirc()
        .args(["evaluate", "--format", "json"])
        .arg(out.join("inverse.toml"))
        .output()
        .unwrap();
    assert_eq!(
        run.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let eval: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
    let hausdorff = eval["fit"]["path_hausdorff_mm"].as_f64().unwrap();
    assert!(hausdorff <= tolerance, "{hausdorff}");
    let objectives = eval["objectives"].as_array().unwrap();
    assert_eq!(objectives.len(), 9);
    assert!(
        objectives.iter().all(|o| o["violation"] == 0.0),
        "{objectives:?}"
    );
}

#[test]
fn inverse_refuses_bad_input_by_name_with_exit_2_and_writes_nothing() {
    let dir = temp("inverse-bad");
    let few = dir.join("few.csv");
    std::fs::write(&few, "0,0\n10,0\n10,10\n").unwrap();
    let cases: [(Vec<String>, &str); 3] = [
        (
            vec!["--target".into(), few.display().to_string()],
            "needs at least 4 points, got 3",
        ),
        (vec![], "no target: give --target FILE"),
        (
            vec![
                "--target".into(),
                concat!(
                    env!("CARGO_MANIFEST_DIR"),
                    "/../../scenes/targets/drawn-loop.toml"
                )
                .into(),
                "--split".into(),
                "half".into(),
            ],
            "--split half: expected equal, first-circular, second-circular or a share",
        ),
    ];
    for (args, says) in cases {
        assert_refused("inverse", &args, says, &dir.join("out"));
    }
}

#[test]
fn repair_writes_the_repaired_scene_and_refuses_bad_input_with_exit_2() {
    let dir = temp("repair");
    let out = dir.join("out");
    let run = noncirc()
        .args(["repair", "--quiet", "--format", "json", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(0), "{stderr}");
    let summary: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
    assert_eq!(summary["scene"], "paper-search");
    assert_eq!(summary["repaired"], true);
    // The written scene is a scene every command takes, and its design meets every
    // objective: `evaluate` exits 0 on it.
    let repaired = out.join("repaired.toml");
    let evaluate = noncirc().arg("evaluate").arg(&repaired).output().unwrap();
    assert_eq!(
        evaluate.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&evaluate.stdout)
    );
    assert!(out.join("repair.json").exists());
    let cases: [(&[&str], &str); 4] = [
        (
            &["--design-scale", "0"],
            "repair's design scale 0: expected above 0",
        ),
        (
            &["--path-tolerance-mm", "nan"],
            "repair's path tolerance (mm) NaN",
        ),
        (
            &["--resume", "x.json"],
            "neither writes nor resumes a checkpoint",
        ),
        (
            &["ellipse-gear"],
            "repair needs a three_arm or transplanter scene",
        ),
    ];
    for (args, says) in cases {
        assert_refused("repair", args, says, &dir.join("bad"));
    }
}

#[test]
fn seeds_and_budgets_over_the_whole_u64_range_travel_through_every_file() {
    // TOML's integers stop at 2^63 − 1: above, the scene writes a decimal string and reads
    // either back; the search's outputs and its checkpoint keep the number.
    let dir = temp("u64");
    for seed in [
        "0",
        "9223372036854775807",
        "9223372036854775808",
        "18446744073709551615",
    ] {
        let out = dir.join(format!("out-{seed}"));
        let ck = dir.join(format!("ck-{seed}.json"));
        let run = noncirc()
            .args([
                "optimise",
                "--seed",
                seed,
                "--budget",
                "300",
                "--checkpoint",
            ])
            .arg(&ck)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(0), "{seed}: {stderr}");
        let best = std::fs::read_to_string(out.join("best.toml")).unwrap();
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap())
                .unwrap();
        assert_eq!(summary["seed"].to_string(), seed);
        // The written scene reads back with its seed, as a scene and through --set.
        let again = noncirc()
            .args(["optimise", "--budget", "100", "--format", "json"])
            .arg(out.join("best.toml"))
            .output()
            .unwrap();
        assert_eq!(again.status.code(), Some(0), "{seed}: {best}");
        let again: serde_json::Value = serde_json::from_slice(&again.stdout).unwrap();
        assert_eq!(again["seed"].to_string(), seed, "{best}");
        let set = noncirc()
            .args(["evaluate", "--set", &format!("tolerances.seed={seed}")])
            .args(["--set", &format!("search.budget=\"{seed}\"")])
            .output()
            .unwrap();
        assert_eq!(
            set.status.code(),
            Some(0),
            "{}",
            String::from_utf8_lossy(&set.stderr)
        );
        // The checkpoint resumes to the same result.
        let resumed = noncirc()
            .args(["optimise", "--format", "json", "--resume"])
            .arg(&ck)
            .output()
            .unwrap();
        assert_eq!(resumed.status.code(), Some(0), "{seed}");
        let resumed: serde_json::Value = serde_json::from_slice(&resumed.stdout).unwrap();
        assert_eq!(resumed["seed"].to_string(), seed);
        assert_eq!(resumed["best"], summary["best"], "{seed}");
    }
    // One past the range, or not a number, is refused by name.
    for bad in ["18446744073709551616", "\"12a\"", "-1", "1.5"] {
        let run = noncirc()
            .args(["evaluate", "--set", &format!("search.seed={bad}")])
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "{bad}: {stderr}");
        assert!(
            stderr.contains("search.seed") && stderr.contains("whole number"),
            "{stderr}"
        );
    }
}

#[test]
fn a_checkpoint_path_is_checked_before_the_search_and_a_failed_write_is_said_at_once() {
    // A path that cannot be written: refused before any evaluation (exit 2, the path).
    let run = noncirc()
        .args(["optimise", "--checkpoint", "/nonexistent/dir/ck.json"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("/nonexistent/dir/ck.json"), "{stderr}");
    assert!(run.stdout.is_empty());
    // A state is written before the first evaluation: `kill -9` leaves one to resume, and
    // a periodic write that fails later is said while the search goes on.
    let dir = temp("ckpt-early");
    let sub = dir.join("sub");
    std::fs::create_dir_all(&sub).unwrap();
    let cp = sub.join("run.json");
    let mut child = long_search(&cp)
        .args(["--checkpoint-every", "0"])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    wait_until(|| cp.exists());
    let kept = dir.join("kept.json");
    std::fs::copy(&cp, &kept).unwrap();
    // The search writes into it at every generation: removing it may race with a write.
    wait_until(|| std::fs::remove_dir_all(&sub).is_ok());
    let stderr = child.stderr.take().unwrap();
    let (tell, told) = std::sync::mpsc::channel();
    // Reads on to the end: a closed pipe would end the search.
    let reader = std::thread::spawn(move || {
        use std::io::BufRead;
        let lines = std::io::BufReader::new(stderr)
            .lines()
            .map_while(|l| l.ok());
        let warnings: Vec<String> = lines
            .filter(|l| l.contains("warning") && l.contains("checkpoint"))
            .inspect(|l| tell.send(l.clone()).unwrap_or(()))
            .collect();
        warnings
    });
    // A guard against a hang, not a timing claim.
    let line = told
        .recv_timeout(Duration::from_secs(60))
        .expect("a warning");
    // Said while the search still runs.
    assert!(child.try_wait().unwrap().is_none());
    assert!(
        line.contains("run.json") && line.contains("goes on"),
        "{line}"
    );
    std::thread::sleep(Duration::from_millis(500));
    interrupt(&child);
    assert_eq!(child.wait().unwrap().code(), Some(130));
    // Said once, not at every generation that fails the same way.
    assert_eq!(reader.join().unwrap().len(), 1);
    assert_resumes(&kept, "200");
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn out_refuses_files_it_did_not_write_for_the_scene_unless_forced() {
    // The rule of --checkpoint for --out: a user's own best.toml, or another scene's
    // results, are refused before the search (exit 2, nothing written); a re-run of the
    // same scene replaces its own outputs; --force writes anyway.
    let dir = temp("out-rule");
    let out = dir.join("out");
    std::fs::create_dir_all(&out).unwrap();
    std::fs::write(out.join("best.toml"), "my notes").unwrap();
    let run = |extra: &[&str]| {
        noncirc()
            .args(["optimise", "--budget", "100", "--out"])
            .arg(&out)
            .args(extra)
            .output()
            .unwrap()
    };
    let refused = run(&[]);
    let stderr = String::from_utf8_lossy(&refused.stderr);
    assert_eq!(refused.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("best.toml") && stderr.contains("--force"),
        "{stderr}"
    );
    assert!(refused.stdout.is_empty(), "no search ran");
    assert_eq!(
        std::fs::read_to_string(out.join("best.toml")).unwrap(),
        "my notes"
    );
    assert!(!out.join("summary.json").exists());
    std::fs::remove_file(out.join("best.toml")).unwrap();
    assert_eq!(run(&[]).status.code(), Some(0));
    assert_eq!(run(&[]).status.code(), Some(0), "its own outputs");
    let other = run(&["two-arm"]);
    let stderr = String::from_utf8_lossy(&other.stderr);
    assert_eq!(other.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("'paper-search', not 'two-arm'"), "{stderr}");
    assert_eq!(run(&["two-arm", "--force"]).status.code(), Some(0));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["scene"], "two-arm");
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn a_built_in_s_name_means_the_built_in_and_compare_refuses_a_gear_scene() {
    // A file (or directory) named `paper` in the working directory no longer takes the
    // built-in's place unseen: `paper` is the built-in, `./paper` the file.
    let dir = temp("shadow");
    std::fs::write(dir.join("paper"), "not a scene").unwrap();
    let run = |scene: &str| {
        noncirc()
            .current_dir(&dir)
            .args(["evaluate", scene, "--format", "json"])
            .output()
            .unwrap()
    };
    let builtin = run("paper");
    assert_eq!(builtin.status.code(), Some(0));
    let file = run("./paper");
    let stderr = String::from_utf8_lossy(&file.stderr);
    assert_eq!(file.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("./paper"), "{stderr}");
    let compare = noncirc()
        .args(["compare", "ellipse-gear", "--budget", "100"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&compare.stderr);
    assert_eq!(compare.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("'ellipse-gear'") && stderr.contains("three_arm"),
        "{stderr}"
    );
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn search_constraints_are_reported_by_evaluate_and_refused_by_name_where_unmeasurable() {
    let run = |args: &[&str]| noncirc().args(args).output().unwrap();
    let set = r#"search.constraints=["picking_height_mm <= -90", "loop_width_mm >= 1000"]"#;
    let json = run(&["evaluate", "--set", set, "--format", "json"]);
    assert_eq!(json.status.code(), Some(0));
    let v: serde_json::Value = serde_json::from_slice(&json.stdout).unwrap();
    let measure = |name: &str| {
        (v["measures"].as_array().unwrap().iter())
            .find(|m| m["name"] == name)
            .unwrap()["value"]
            .as_f64()
            .unwrap()
    };
    let c = v["constraints"].as_array().unwrap();
    assert_eq!(c[0]["label"], "picking_height_mm <= -90");
    assert_eq!(
        c[0]["value"].as_f64().unwrap(),
        measure("picking_height_mm")
    );
    assert_eq!(c[0]["upper"].as_f64().unwrap(), -90.0);
    // No loop is a metre wide: missed, by its width's distance to 1000 mm, so the paper's
    // design is infeasible under it.
    let width = measure("loop_width_mm");
    assert_eq!(c[1]["violation"].as_f64().unwrap(), 1000.0 - width);
    assert_eq!(v["feasible"], false);
    let table = run(&["evaluate", "--set", set]);
    let text = String::from_utf8(table.stdout).unwrap();
    assert!(
        text.contains("search constraints:") && text.contains("loop_width_mm >= 1000"),
        "{text}"
    );
    for (constraint, named) in [
        ("box_travel_mm <= 3", "needs a moving box"),
        ("path_rms_mm <= 1", "the scene has no [target]"),
        ("loop_widht_mm <= 50", "loop_width_mm"),
        ("loop_width_mm < 50", "NAME <= VALUE"),
        ("loop_width_mm <= 1e999", "its bound"),
    ] {
        let set = format!(r#"search.constraints=["{constraint}"]"#);
        let out = run(&["optimise", "--set", &set]);
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(out.status.code(), Some(2), "{constraint}: {err}");
        assert!(err.contains(named), "{constraint}: {err}");
    }
    let twice = r#"search.constraints=["loop_width_mm <= 50", "loop_width_mm <= 50"]"#;
    let out = run(&["evaluate", "--set", twice]);
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(err.contains("listed twice"), "{err}");
}
