//! Records the git revision (if the source is a git checkout) for the MCAP metadata.
//!
//! Cargo reruns this script (and rebuilds the library and everything above it) when a file it
//! watches changes or is missing, so it watches only files that exist: the checkout's HEAD and
//! the branch it points to, wherever git keeps them (in a linked worktree `.git` is a file and
//! HEAD lives in the main repository's `.git/worktrees/NAME/`).
use std::path::PathBuf;
use std::process::Command;

/// The output of `git ARGS` run in this crate's directory, trimmed; `None` outside a checkout
/// or without git.
fn git(args: &[&str]) -> Option<String> {
    Command::new("git")
        .args(args)
        .output()
        .ok()
        .filter(|o| o.status.success())
        .and_then(|o| String::from_utf8(o.stdout).ok())
        .map(|s| s.trim().to_string())
        .filter(|s| !s.is_empty())
}

/// The files whose change means another revision: HEAD, and the branch it points to (its own
/// file, or the packed refs when it has none), so that commits on other branches rebuild
/// nothing.
fn watched() -> Vec<PathBuf> {
    let here = std::env::current_dir().unwrap_or_default();
    let dir = |arg: &str| git(&["rev-parse", arg]).map(|d| here.join(d));
    let (Some(git_dir), Some(common)) = (dir("--git-dir"), dir("--git-common-dir")) else {
        return Vec::new();
    };
    let mut paths = vec![git_dir.join("HEAD")];
    if let Some(branch) = git(&["symbolic-ref", "-q", "HEAD"]) {
        paths.push(common.join(branch));
        paths.push(common.join("packed-refs"));
    }
    paths.into_iter().filter(|p| p.exists()).collect()
}

fn main() {
    let revision =
        git(&["rev-parse", "--short=12", "HEAD"]).unwrap_or_else(|| "unknown".to_string());
    println!("cargo:rustc-env=FLEXRIG_GIT_REVISION={revision}");
    println!("cargo:rerun-if-changed=build.rs");
    for path in watched() {
        println!("cargo:rerun-if-changed={}", path.display());
    }
}
