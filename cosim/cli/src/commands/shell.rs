//! `crane-cosim completions SHELL` and `crane-cosim man`: shell completions and manual pages
//! generated from the clap definitions, so that they cannot drift from `--help`.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{bail, Context, Result};
use clap::Args;
use clap_complete::Shell;

/// The binary's name as the shells and `man` know it.
const NAME: &str = "crane-cosim";

/// Arguments of `crane-cosim completions`.
#[derive(Debug, Args)]
pub struct CompletionsArgs {
    /// The shell to complete for; the script goes to standard output (e.g. `crane-cosim
    /// completions bash > ~/.local/share/bash-completion/completions/crane-cosim`).
    #[arg(value_enum)]
    pub shell: Shell,
}

/// Arguments of `crane-cosim man`.
#[derive(Debug, Args)]
pub struct ManArgs {
    /// Write one page per command into this folder (crane-cosim.1, crane-cosim-run.1, …; created
    /// if missing) instead of printing the main page; a file there of the same name is replaced
    /// only if it is a page of the same command.
    #[arg(short = 'o', long = "output", value_name = "DIR")]
    pub output: Option<PathBuf>,
}

/// Prints the completion script of `command` (the whole command line) for `args.shell`.
pub fn completions(args: &CompletionsArgs, mut command: clap::Command) -> Result<()> {
    let mut script = Vec::new();
    clap_complete::generate(args.shell, &mut command, NAME, &mut script);
    if args.shell == Shell::Bash {
        script = hyphen_fixed(&String::from_utf8_lossy(&script)).into_bytes();
    }
    let mut out = std::io::stdout().lock();
    out.write_all(&script)?;
    Ok(out.flush()?)
}

/// The bash script with its `case` arms spelt as its dispatch loop spells the subcommand state.
/// Why: for a binary name with a hyphen, clap_complete (4.6) escapes the name once in the loop
/// (`crane__cosim__subcmd__run`) and together with the path in the arms
/// (`crane__subcmd__cosim__subcmd__run`), so no arm matches and nothing after a subcommand
/// completes (clap-rs/clap issues 6421 and 6529). Once fixed upstream this replaces nothing.
fn hyphen_fixed(script: &str) -> String {
    script.replace("crane__subcmd__cosim", "crane__cosim")
}

/// Prints the main manual page of `command` (the whole command line), or writes every
/// command's page into `args.output`.
pub fn man(args: &ManArgs, command: clap::Command) -> Result<()> {
    let mut command = command.disable_help_subcommand(true);
    // Building sets the subcommands' display names (crane-cosim-run), which name their pages.
    command.build();
    let Some(dir) = &args.output else {
        let mut out = std::io::stdout().lock();
        clap_mangen::Man::new(command).render(&mut out)?;
        return Ok(out.flush()?);
    };
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create the folder {}", dir.display()))?;
    let mut written = 0;
    for page in pages(command) {
        write_page(&page, dir)?;
        written += 1;
    }
    println!("wrote {written} manual pages to {}", dir.display());
    Ok(())
}

/// The command and every visible subcommand, depth first.
fn pages(command: clap::Command) -> Vec<clap::Command> {
    let mut all = vec![command.clone()];
    for sub in command.get_subcommands().filter(|s| !s.is_hide_set()) {
        all.extend(pages(sub.clone()));
    }
    all
}

/// Renders `command`'s page into `dir`, refusing to replace a file that is not a page of it.
fn write_page(command: &clap::Command, dir: &Path) -> Result<()> {
    let man = clap_mangen::Man::new(command.clone());
    let path = dir.join(man.get_filename());
    let name = command.get_display_name().unwrap_or_else(|| command.get_name());
    if let Ok(existing) = std::fs::read(&path) {
        let title = format!(".TH {name} ");
        if !String::from_utf8_lossy(&existing).lines().any(|line| line.starts_with(&title)) {
            bail!(
                "{} exists and is not the manual page of {name}: not replaced (move it, or choose another folder)",
                path.display()
            );
        }
    }
    let mut page = Vec::new();
    man.render(&mut page)?;
    std::fs::write(&path, page).with_context(|| format!("cannot write {}", path.display()))
}
