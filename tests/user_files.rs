//! Issue 9, "The user's data": `--csv` never replaces the scene (same path, a symbolic link
//! or a hard link to it), and a write that fails half-way leaves the previous CSV as it was.

use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

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
