//! `crane-cosim completions SHELL` and `crane-cosim man`, tested as a user uses them: the bash
//! script sourced into bash and asked to complete, the manual pages written and read back.

#[path = "../../test_support.rs"]
mod common;

use common::{crane_cosim, text};

use std::path::Path;
use std::process::Command;

/// What bash's completion offers for the words `line` (the last one being completed), with the
/// script of `crane-cosim completions bash` sourced.
fn bash_completes(script: &Path, line: &[&str]) -> Vec<String> {
    let words = line.iter().map(|w| format!("'{w}'")).collect::<Vec<_>>().join(" ");
    let (cur, prev) = (line[line.len() - 1], line[line.len() - 2]);
    let program = format!(
        "source '{}'; COMP_WORDS=({words}); COMP_CWORD={}; _crane__cosim crane-cosim '{cur}' '{prev}'; \
         printf '%s\\n' \"${{COMPREPLY[@]}}\"",
        script.display(),
        line.len() - 1
    );
    let out = Command::new("bash").args(["-c", &program]).output().expect("bash runs");
    assert!(out.status.success(), "{}", text(&out.stderr));
    text(&out.stdout).lines().map(String::from).collect()
}

#[test]
fn the_bash_script_completes_subcommands_options_and_their_values() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = crane_cosim(&["completions", "bash"], dir.path());
    assert!(out.status.success(), "{}", text(&out.stderr));
    let script = dir.path().join("crane-cosim.bash");
    std::fs::write(&script, &out.stdout).expect("write script");
    assert_eq!(bash_completes(&script, &["crane-cosim", "cam"]), ["campaign"]);
    // Past a subcommand (what clap_complete 4.6 gets wrong for a hyphenated binary name).
    assert_eq!(
        bash_completes(&script, &["crane-cosim", "run", "--st"]),
        ["--start", "--stop-time", "--step-size", "--step-timeout"]
    );
    assert_eq!(bash_completes(&script, &["crane-cosim", "campaign", "--scale", ""]), ["test", "full"]);
    assert_eq!(bash_completes(&script, &["crane-cosim", "sweep", "p"]), ["plan"]);
}

#[test]
fn zsh_fish_and_powershell_scripts_name_the_commands() {
    let dir = tempfile::tempdir().expect("tempdir");
    let script = |shell: &str| {
        let out = crane_cosim(&["completions", shell], dir.path());
        assert!(out.status.success(), "{shell}: {}", text(&out.stderr));
        text(&out.stdout)
    };
    assert!(script("zsh").starts_with("#compdef crane-cosim"));
    let fish = script("fish");
    assert!(
        fish.contains("complete -c crane-cosim -n \"__fish_crane_cosim_needs_command\" -f -a \"campaign\""),
        "{fish}"
    );
    assert!(script("powershell").contains("'crane-cosim;run'"));
    let refused = crane_cosim(&["completions", "tcsh"], dir.path());
    assert!(!refused.status.success() && text(&refused.stderr).contains("possible values"));
}

#[test]
fn man_writes_a_page_per_command_and_replaces_only_its_own() {
    let dir = tempfile::tempdir().expect("tempdir");
    let pages = dir.path().join("man");
    let out = crane_cosim(&["man", "-o", "man"], dir.path());
    assert!(out.status.success(), "{}", text(&out.stderr));
    // The command, its 12 subcommands and the sweep's 3.
    assert_eq!(text(&out.stdout).trim(), "wrote 16 manual pages to man");
    let run = std::fs::read_to_string(pages.join("crane-cosim-run.1")).expect("run's page");
    assert!(run.contains(".TH crane-cosim-run 1"), "{run}");
    assert!(run.contains(".SH OPTIONS") && run.contains("\\-\\-step\\-size"), "{run}");
    assert!(pages.join("crane-cosim-sweep-plan.1").is_file());
    // Written again over its own pages; a foreign file of a page's name is left alone.
    assert!(crane_cosim(&["man", "-o", "man"], dir.path()).status.success());
    std::fs::write(pages.join("crane-cosim-view.1"), "my notes\n").expect("write");
    let refused = crane_cosim(&["man", "-o", "man"], dir.path());
    assert!(!refused.status.success());
    assert!(text(&refused.stderr).contains("is not the manual page of crane-cosim-view: not replaced"));
    assert_eq!(std::fs::read_to_string(pages.join("crane-cosim-view.1")).expect("read"), "my notes\n");
    // Without -o: the main page on standard output.
    let main = crane_cosim(&["man"], dir.path());
    assert!(text(&main.stdout).contains(".TH crane-cosim 1"));
}
