//! Issue 9, "The user's data": `--csv` never replaces the scene (same path, a symbolic link
//! or a hard link to it), and a write that fails half-way leaves the previous CSV as it was.
//! Issue 22, "Nothing lost, nothing leaked": no option of any command writes onto an input
//! (scene, cam file), a link planted at a temporary name is never followed, no temporary file
//! survives an error or SIGTERM; a cam file a scene names is confined to the scene's folder,
//! a regular file, and its content is never quoted.

use std::collections::BTreeMap;
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use mechdiff::{Error, files};

/// A fresh directory for one test, with a copy of the slider-crank scene in it.
fn workspace(test: &str) -> (PathBuf, PathBuf) {
    let dir = std::env::temp_dir().join(format!("mechdiff-files-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("s.toml");
    let source = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/slider_crank.toml");
    std::fs::copy(source, &scene).unwrap();
    (dir, scene)
}

fn mechdiff(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_mechdiff"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the mechdiff binary runs")
}

/// The files left in `dir`, sorted (a stray temporary file would show here).
fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// `mechdiff run s.toml --csv s.toml` (and `./s.toml`, a symbolic link, a hard link):
/// refused before anything is written; the scene is unchanged.
#[test]
fn csv_onto_the_scene_is_refused_through_any_name() {
    let (dir, scene) = workspace("same");
    let original = std::fs::read(&scene).unwrap();
    #[cfg(unix)]
    std::os::unix::fs::symlink("s.toml", dir.join("link.toml")).unwrap();
    std::fs::hard_link(&scene, dir.join("hard.toml")).unwrap();
    let mut targets = vec!["s.toml", "./s.toml", "hard.toml"];
    if cfg!(unix) {
        targets.push("link.toml");
    }
    for target in targets {
        let output = mechdiff(&dir, &["run", "s.toml", "--csv", target]);
        assert!(!output.status.success(), "--csv {target} was accepted");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(
            stderr.contains(&format!(
                "refusing to write {target}: it is the scene file s.toml"
            )),
            "{stderr}"
        );
        assert!(
            output.stdout.is_empty(),
            "nothing is printed before the refusal"
        );
        assert_eq!(std::fs::read(&scene).unwrap(), original, "--csv {target}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A full disk, simulated by a file size limit of 1 KiB (`ulimit -f 1`, with SIGXFSZ ignored
/// so the write returns EFBIG as on a full disk): the run fails with the reason, the
/// previous CSV is intact, and no temporary file is left.
#[cfg(unix)]
#[test]
fn a_write_that_fails_half_way_leaves_the_previous_csv_intact() {
    let (dir, _) = workspace("full");
    let previous = "phi [deg],s [mm]\n0,1\n";
    std::fs::write(dir.join("out.csv"), previous).unwrap();
    let output = Command::new("sh")
        .arg("-c")
        .arg(r#"trap '' XFSZ; ulimit -f 1 && exec "$0" run s.toml --csv out.csv"#)
        .arg(env!("CARGO_BIN_EXE_mechdiff"))
        .current_dir(&dir)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success(), "the write should fail: {stderr}");
    assert!(stderr.contains("cannot write out.csv"), "{stderr}");
    assert_eq!(
        std::fs::read_to_string(dir.join("out.csv")).unwrap(),
        previous
    );
    assert_eq!(listing(&dir), ["out.csv", "s.toml"]);
    // Without the limit the same command replaces the CSV with the whole table (74 lines:
    // the header and 73 positions).
    let output = mechdiff(&dir, &["run", "s.toml", "--csv", "out.csv"]);
    assert!(output.status.success());
    assert_eq!(
        std::fs::read_to_string(dir.join("out.csv"))
            .unwrap()
            .lines()
            .count(),
        74
    );
    assert_eq!(listing(&dir), ["out.csv", "s.toml"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A writer that fails after `budget` bytes, like a disk that fills up.
struct FailsAfter<'a> {
    inner: &'a mut dyn Write,
    budget: usize,
}

impl Write for FailsAfter<'_> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        if self.budget == 0 {
            return Err(io::Error::other("injected: no space left"));
        }
        let n = buf.len().min(self.budget);
        self.budget -= n;
        self.inner.write(&buf[..n])
    }

    fn flush(&mut self) -> io::Result<()> {
        self.inner.flush()
    }
}

/// The same in-process, with the error injected after 100 bytes (more than the buffer of one
/// line, less than the whole output): the error is reported with the path, the old file is
/// intact, no temporary file is left; a complete write replaces it.
#[test]
fn an_injected_write_error_leaves_the_previous_file_intact() {
    let (dir, _) = workspace("injected");
    let path = dir.join("out.csv");
    std::fs::write(&path, "previous\n").unwrap();
    let long = "0123456789,".repeat(10_000);
    let e = files::write_atomically(&path, |out| {
        let mut failing = FailsAfter {
            inner: out,
            budget: 100,
        };
        failing.write_all(long.as_bytes())?;
        failing.flush()
    })
    .unwrap_err();
    assert!(matches!(e, Error::Write { .. }), "{e:?}");
    assert!(e.to_string().contains("injected: no space left"), "{e}");
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "previous\n");
    assert_eq!(listing(&dir), ["out.csv", "s.toml"]);
    files::write_atomically(&path, |out| out.write_all(long.as_bytes())).unwrap();
    assert_eq!(std::fs::read_to_string(&path).unwrap(), long);
    assert_eq!(listing(&dir), ["out.csv", "s.toml"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `same_file` sees through links and `..`, and a path that does not exist is no file's.
#[test]
fn same_file_compares_the_files_not_the_names() {
    let (dir, scene) = workspace("same-file");
    let detour = dir.join("sub");
    std::fs::create_dir(&detour).unwrap();
    assert!(files::same_file(&scene, &detour.join("../s.toml")));
    assert!(!files::same_file(&scene, &dir.join("other.csv")));
    std::fs::write(dir.join("copy.toml"), std::fs::read(&scene).unwrap()).unwrap();
    assert!(
        !files::same_file(&scene, &dir.join("copy.toml")),
        "equal content, other file"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Every file under `dir` (recursively, hidden ones too) with its bytes, a symbolic link as
/// the path it points to: equal before and after a command means nothing was written,
/// replaced or left behind.
fn snapshot(dir: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    let mut files = BTreeMap::new();
    let mut pending = vec![dir.to_owned()];
    while let Some(d) = pending.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let path = entry.unwrap().path();
            let kind = std::fs::symlink_metadata(&path).unwrap().file_type();
            if kind.is_symlink() {
                let target = std::fs::read_link(&path).unwrap();
                files.insert(path, target.as_os_str().as_encoded_bytes().to_vec());
            } else if kind.is_dir() {
                pending.push(path);
            } else {
                files.insert(path.clone(), std::fs::read(&path).unwrap());
            }
        }
    }
    files
}

/// The cam-driven rocker in `dir` as `rocker.toml`, its `[drive] cam` written `cam`; the
/// shipped cam copied to `dir/cams/cam.toml`.
fn rocker(dir: &Path, cam: &str) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    std::fs::create_dir_all(dir.join("cams")).unwrap();
    std::fs::copy(
        root.join("cams/rise_dwell_return_dwell.toml"),
        dir.join("cams/cam.toml"),
    )
    .unwrap();
    let text = std::fs::read_to_string(root.join("cam_driven_rocker.toml")).unwrap();
    let line = "cam = \"cams/rise_dwell_return_dwell.toml\"";
    assert!(text.contains(line));
    let text = text.replace(line, &format!("cam = {cam:?}"));
    std::fs::write(dir.join("rocker.toml"), text).unwrap();
}

/// Issue 22's examples and their variants: every option that writes a file, aimed at one of
/// the run's inputs (the scene; the cam file a cam-driven scene reads; a scene inside the
/// `--plot` folder named as one of its pictures) is refused with both named, and nothing in
/// the folder changes (bytes equal, no file added).
#[test]
fn no_option_of_any_command_writes_onto_an_input() {
    let (dir, scene) = workspace("onto-inputs");
    rocker(&dir, "cams/cam.toml");
    for (folder, name) in [
        ("pd", "report.html"),
        ("pd2", "diagram.svg"),
        ("pd3", "diagram.png"),
    ] {
        std::fs::create_dir(dir.join(folder)).unwrap();
        std::fs::copy(&scene, dir.join(folder).join(name)).unwrap();
    }
    let cam = "cams/cam.toml";
    let quick = ["--positions", "2", "--repeats", "1"];
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec!["run", "rocker.toml", "--csv", cam], "the cam file"),
        (vec!["run", "rocker.toml", "--json", cam], "the cam file"),
        (vec!["run", "rocker.toml", "--jsonl", cam], "the cam file"),
        (vec!["run", "rocker.toml", "--report", cam], "the cam file"),
        (
            vec!["run", "rocker.toml", "--csv", "rocker.toml"],
            "the scene file",
        ),
        (vec!["run", cam, "--profile-csv", cam], "the scene file"),
        (
            vec!["run", cam, "--csv", "./cams/../cams/cam.toml"],
            "the scene file",
        ),
        (
            [&["accuracy", "s.toml", "--csv", "s.toml"][..], &quick].concat(),
            "the scene file",
        ),
        (
            [&["accuracy", "s.toml", "--svg", "s.toml"][..], &quick].concat(),
            "the scene file",
        ),
        (
            [&["accuracy", "rocker.toml", "--csv", cam][..], &quick].concat(),
            "the cam file",
        ),
        (
            vec!["run", "pd/report.html", "--plot", "pd"],
            "the scene file",
        ),
        (
            vec!["run", "pd2/diagram.svg", "--plot", "pd2"],
            "the scene file",
        ),
        (
            vec!["run", "pd3/diagram.png", "--plot", "pd3"],
            "the scene file",
        ),
    ];
    let before = snapshot(&dir);
    for (args, role) in cases {
        let output = mechdiff(&dir, &args);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(!output.status.success(), "{args:?} was accepted");
        assert!(stderr.contains("refusing to write"), "{args:?}: {stderr}");
        assert!(
            stderr.contains(&format!("it is {role} ")),
            "{args:?}: {stderr}"
        );
        assert_eq!(snapshot(&dir), before, "{args:?} changed the folder");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Symbolic links to the scene planted at every temporary name the old writers used
/// (`FILE.tmp`, `FILE.partial`, `.FILE.tmp`) are never followed: the scene is unchanged, the
/// links are still the same links, and the outputs are written.
#[cfg(unix)]
#[test]
fn links_planted_at_temporary_names_are_never_followed() {
    let (dir, scene) = workspace("planted");
    let original = std::fs::read(&scene).unwrap();
    std::fs::create_dir(dir.join("pd")).unwrap();
    let planted = [
        "r.html.tmp",
        ".r.html.tmp",
        "out.csv.tmp",
        "out.partial",
        ".out.csv.tmp",
        "acc.partial",
        "acc.csv.tmp",
        "pd/report.html.tmp",
        "pd/diagram.svg.tmp",
        "pd/diagram.png.tmp",
    ];
    for name in planted {
        std::os::unix::fs::symlink(&scene, dir.join(name)).unwrap();
    }
    let runs: [&[&str]; 2] = [
        &[
            "run", "s.toml", "--report", "r.html", "--csv", "out.csv", "--plot", "pd",
        ],
        &[
            "accuracy",
            "s.toml",
            "--csv",
            "acc.csv",
            "--positions",
            "2",
            "--repeats",
            "1",
        ],
    ];
    for args in runs {
        let output = mechdiff(&dir, args);
        assert!(
            output.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&output.stderr)
        );
    }
    assert_eq!(std::fs::read(&scene).unwrap(), original);
    for name in planted {
        assert_eq!(std::fs::read_link(dir.join(name)).unwrap(), scene, "{name}");
    }
    for written in [
        "r.html",
        "out.csv",
        "acc.csv",
        "pd/report.html",
        "pd/diagram.svg",
    ] {
        assert!(
            std::fs::metadata(dir.join(written)).unwrap().len() > 0,
            "{written}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Writes that fail half-way (a file size limit of 1 KiB, as a full disk) of the report, the
/// accuracy SVG and the cam CSV leave no temporary file, and the previous file as it was.
#[cfg(unix)]
#[test]
fn failed_writes_of_every_kind_leave_no_temporary_file() {
    let (dir, _) = workspace("full-every");
    rocker(&dir, "cams/cam.toml");
    let previous = "previous\n";
    let cases = [
        ("run s.toml --report r.html", "r.html"),
        (
            "accuracy s.toml --svg a.svg --positions 2 --repeats 1",
            "a.svg",
        ),
        ("run cams/cam.toml --csv c.csv", "c.csv"),
        ("run rocker.toml --json j.json", "j.json"),
    ];
    for (_, out) in cases {
        std::fs::write(dir.join(out), previous).unwrap();
    }
    let before = snapshot(&dir);
    for (args, out) in cases {
        let output = Command::new("sh")
            .arg("-c")
            .arg(format!(r#"trap '' XFSZ; ulimit -f 1 && exec "$0" {args}"#))
            .arg(env!("CARGO_BIN_EXE_mechdiff"))
            .current_dir(&dir)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(!output.status.success(), "{args}: the write should fail");
        assert!(
            stderr.contains(&format!("cannot write {out}")),
            "{args}: {stderr}"
        );
        assert_eq!(snapshot(&dir), before, "{args}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// SIGTERM while a long sweep streams its CSV: the process ends with 143 (128 + 15), its
/// temporary file (seen growing past 64 KiB: mid-write) is gone, and the previous CSV is as
/// it was.
#[cfg(unix)]
#[test]
fn sigterm_mid_write_removes_the_temporary_file_and_keeps_the_old_one() {
    let (dir, scene) = workspace("sigterm");
    // 3.6 million positions: minutes of streaming, stopped within its first seconds.
    let text = std::fs::read_to_string(&scene).unwrap();
    assert!(text.contains("step = 5\n"));
    std::fs::write(
        dir.join("long.toml"),
        text.replace("step = 5\n", "step = 0.0001\n"),
    )
    .unwrap();
    std::fs::write(dir.join("big.csv"), "previous\n").unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_mechdiff"))
        .args(["run", "long.toml", "--csv", "big.csv"])
        .current_dir(&dir)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let deadline = Instant::now() + Duration::from_secs(120);
    let temporary = loop {
        let growing = std::fs::read_dir(&dir).unwrap().find_map(|e| {
            let e = e.unwrap();
            let name = e.file_name().to_string_lossy().into_owned();
            let big = e.metadata().is_ok_and(|m| m.len() >= 1 << 16);
            (name.starts_with(".big.csv.") && name.ends_with(".tmp") && big).then(|| e.path())
        });
        if let Some(path) = growing {
            break path;
        }
        assert!(
            child.try_wait().unwrap().is_none(),
            "the run ended before SIGTERM"
        );
        assert!(Instant::now() < deadline, "no temporary file grew in 120 s");
        std::thread::sleep(Duration::from_millis(20));
    };
    let kill = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(kill.success());
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(143), "{status:?}");
    assert!(!temporary.exists(), "{} left behind", temporary.display());
    assert_eq!(listing(&dir), ["big.csv", "long.toml", "s.toml"]);
    assert_eq!(
        std::fs::read_to_string(dir.join("big.csv")).unwrap(),
        "previous\n"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `[drive] cam` outside the scene's folder — absolute (`/etc/passwd`, issue 22's example),
/// through `..`, through a symbolic link pointing out — is refused with the resolved path,
/// and nothing of the file is quoted; `--allow-path` lets the user name another folder.
#[cfg(unix)]
#[test]
fn a_cam_file_outside_the_scene_folder_is_refused_unless_allowed() {
    let (root, _) = workspace("confined");
    let dir = root.join("scene");
    rocker(&dir, "cams/cam.toml");
    let elsewhere = root.join("elsewhere");
    std::fs::create_dir(&elsewhere).unwrap();
    std::fs::copy(dir.join("cams/cam.toml"), elsewhere.join("cam.toml")).unwrap();
    std::os::unix::fs::symlink("../../elsewhere/cam.toml", dir.join("cams/out.toml")).unwrap();
    std::os::unix::fs::symlink("/etc/passwd", dir.join("cams/passwd.toml")).unwrap();
    let inside = dir.join("cams/cam.toml").display().to_string();
    for cam in ["cams/cam.toml", inside.as_str(), "cams/../cams/cam.toml"] {
        rocker(&dir, cam);
        let output = mechdiff(&dir, &["check", "rocker.toml"]);
        assert!(
            output.status.success(),
            "{cam}: {}",
            String::from_utf8_lossy(&output.stderr)
        );
    }
    for cam in [
        "/etc/passwd",
        "../elsewhere/cam.toml",
        "cams/out.toml",
        "cams/passwd.toml",
    ] {
        rocker(&dir, cam);
        for command in ["check", "run"] {
            let output = mechdiff(&dir, &[command, "rocker.toml"]);
            let stderr = String::from_utf8_lossy(&output.stderr);
            assert!(!output.status.success(), "{cam} accepted by {command}");
            assert!(
                stderr.contains("lies outside the scene's folder"),
                "{cam}: {stderr}"
            );
            assert!(stderr.contains("--allow-path"), "{stderr}");
            assert!(!stderr.contains("root:"), "{cam}: {stderr}");
        }
    }
    for cam in ["../elsewhere/cam.toml", "cams/out.toml"] {
        rocker(&dir, cam);
        let output = mechdiff(
            &dir,
            &["check", "rocker.toml", "--allow-path", "../elsewhere"],
        );
        assert!(
            output.status.success(),
            "{cam}: {}",
            String::from_utf8_lossy(&output.stderr)
        );
    }
    // Allowed, /etc/passwd is still not a cam scene: its place, never its text.
    rocker(&dir, "/etc/passwd");
    let output = mechdiff(&dir, &["check", "rocker.toml", "--allow-path", "/etc"]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success());
    assert!(
        stderr.contains("/etc/passwd:1:") && stderr.contains("not a TOML file"),
        "{stderr}"
    );
    assert!(!stderr.contains("root"), "{stderr}");
    std::fs::remove_dir_all(&root).unwrap();
}

/// A FIFO named as the cam (issue 22: it hung forever) is refused at once, without waiting for
/// a writer; so are a device and a folder.
#[cfg(unix)]
#[test]
fn a_fifo_a_device_or_a_folder_named_as_a_cam_is_refused_without_waiting() {
    let (dir, _) = workspace("fifo");
    rocker(&dir, "cams/cam.toml");
    let made = Command::new("mkfifo")
        .arg(dir.join("cams/pipe.toml"))
        .status()
        .unwrap();
    assert!(made.success());
    let cases = [
        ("cams/pipe.toml", vec![], "a FIFO"),
        (
            "/dev/zero",
            vec!["--allow-path", "/dev"],
            "/proc, /sys or /dev",
        ),
        ("cams", vec![], "a folder"),
    ];
    for (cam, allow, why) in cases {
        rocker(&dir, cam);
        let mut child = Command::new(env!("CARGO_BIN_EXE_mechdiff"))
            .args([&["check", "rocker.toml"][..], &allow].concat())
            .current_dir(&dir)
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // Reading the scene and refusing takes milliseconds; 30 s is a hang.
        let deadline = Instant::now() + Duration::from_secs(30);
        while child.try_wait().unwrap().is_none() {
            if Instant::now() > deadline {
                child.kill().unwrap();
                panic!("`cam = {cam:?}`: still waiting after 30 s");
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        let output = child.wait_with_output().unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(!output.status.success(), "{cam}");
        assert!(
            stderr.contains(why) && stderr.contains("not a regular file"),
            "{cam}: {stderr}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Issue 22's `/proc/self/environ` example and its variants: a secret in the environment, or
/// in a file of the scene's folder that is not a cam scene (not TOML; TOML without `[cam]`),
/// never appears in what the tool prints; the error gives the place instead.
#[cfg(unix)]
#[test]
fn a_secret_read_through_a_scene_never_reaches_the_messages() {
    const SECRET: &str = "s3cr3t-4f2a9c";
    let (dir, _) = workspace("secret");
    rocker(&dir, "cams/cam.toml");
    std::fs::write(
        dir.join("cams/env.toml"),
        format!("HOME=/root\nTOKEN={SECRET}\n"),
    )
    .unwrap();
    std::fs::write(
        dir.join("cams/keys.toml"),
        format!("token = \"{SECRET}\"\n"),
    )
    .unwrap();
    std::fs::write(dir.join("cams/late.toml"), format!("a = 1\nb = {SECRET}\n")).unwrap();
    let cases = [
        (
            "/proc/self/environ",
            vec!["--allow-path", "/proc"],
            "/proc, /sys or /dev",
        ),
        ("/proc/self/environ", vec![], "lies outside"),
        ("cams/env.toml", vec![], "cams/env.toml:1:"),
        ("cams/keys.toml", vec![], "no `[cam]` table"),
        (
            "cams/late.toml",
            vec![],
            "cams/late.toml:2:5: not a TOML file",
        ),
    ];
    for (cam, allow, expected) in cases {
        rocker(&dir, cam);
        for command in ["check", "run"] {
            let output = Command::new(env!("CARGO_BIN_EXE_mechdiff"))
                .args([&[command, "rocker.toml"][..], &allow].concat())
                .current_dir(&dir)
                .env("MECHDIFF_TEST_TOKEN", SECRET)
                .output()
                .unwrap();
            let (out, err) = (
                String::from_utf8_lossy(&output.stdout),
                String::from_utf8_lossy(&output.stderr),
            );
            assert!(!output.status.success(), "{cam}");
            assert!(err.contains(expected), "{cam}: {err}");
            assert!(
                !out.contains(SECRET) && !err.contains(SECRET),
                "{cam}: {err}"
            );
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
