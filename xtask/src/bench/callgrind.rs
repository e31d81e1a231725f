//! Instruction counts from callgrind: running a command under it and reading its profile.
//!
//! The profile format is documented in the valgrind manual ("Callgrind Format Specification").
//! Only what the bench needs is read: the `totals:` line and, for every `fmi2*` function, its
//! inclusive cost (its own cost lines plus the cost lines that follow its `calls=` lines), per
//! shared object.

use anyhow::{bail, Context, Result};
use std::collections::{BTreeMap, HashMap};
use std::path::Path;
use std::process::{Command, Stdio};

/// What one callgrind profile says.
#[derive(Debug, Default, PartialEq, Eq)]
pub struct Profile {
    /// Instructions executed by the whole process (Ir).
    pub total: u64,
    /// Object file name (e.g. `crane.so`) → inclusive instructions of its `fmi2*` functions
    /// together: everything the importer spent inside that library.
    pub entry_points: BTreeMap<String, u64>,
}

/// Runs `program args` under callgrind, pinned to `core`, writing the profile to `out`, and
/// reads the profile.
pub fn profile(core: &str, program: &Path, args: &[&str], out: &Path) -> Result<Profile> {
    let status = Command::new("taskset")
        .args(["-c", core, "valgrind", "--tool=callgrind", "--quiet"])
        .arg(format!("--callgrind-out-file={}", out.display()))
        .arg(program)
        .args(args)
        .stdout(Stdio::null())
        .status()
        .context("cannot start taskset/valgrind (on Debian: apt-get install valgrind util-linux)")?;
    if !status.success() {
        bail!("callgrind run of {} {} failed with {status}", program.display(), args.join(" "));
    }
    let text = std::fs::read_to_string(out).with_context(|| format!("reading {}", out.display()))?;
    parse(&text).with_context(|| format!("parsing {}", out.display()))
}

/// Reads a callgrind profile (compressed or not).
pub fn parse(text: &str) -> Result<Profile> {
    let mut reader = Reader::default();
    for line in text.lines() {
        reader.line(line)?;
    }
    let Some(total) = reader.total else { bail!("no 'totals:' or 'summary:' line: not a complete callgrind profile") };
    Ok(Profile { total, entry_points: reader.entry_points })
}

/// The parser's state between lines.
#[derive(Default)]
struct Reader {
    /// Name-compression tables: `ob`/`cob` share one, `fn`/`cfn` another.
    objects: HashMap<String, String>,
    functions: HashMap<String, String>,
    /// Position columns before the events on a cost line (`positions:` header, default 1).
    positions: Option<usize>,
    /// Index of `Ir` among the events (`events:` header).
    ir_index: usize,
    object: String,
    /// The current function is an FMI entry point: its cost lines count.
    counting: bool,
    total: Option<u64>,
    entry_points: BTreeMap<String, u64>,
}

impl Reader {
    fn line(&mut self, line: &str) -> Result<()> {
        if let Some(rest) = line.strip_prefix("ob=") {
            self.object = expand(&mut self.objects, rest)?;
        } else if let Some(rest) = line.strip_prefix("cob=") {
            expand(&mut self.objects, rest)?;
        } else if let Some(rest) = line.strip_prefix("fn=") {
            let function = expand(&mut self.functions, rest)?;
            self.counting = function.starts_with("fmi2");
        } else if let Some(rest) = line.strip_prefix("cfn=") {
            expand(&mut self.functions, rest)?;
        } else if let Some(rest) = line.strip_prefix("positions:") {
            self.positions = Some(rest.split_whitespace().count());
        } else if let Some(rest) = line.strip_prefix("events:") {
            let Some(index) = rest.split_whitespace().position(|e| e == "Ir") else {
                bail!("the profile has no Ir event: {line}")
            };
            self.ir_index = index;
        } else if let Some(rest) = line.strip_prefix("totals:").or_else(|| line.strip_prefix("summary:")) {
            let ir = rest.split_whitespace().nth(self.ir_index).unwrap_or("0");
            self.total = Some(ir.parse().with_context(|| format!("bad totals line: {line}"))?);
        } else if self.counting && line.starts_with(|c: char| c.is_ascii_digit() || "+-*".contains(c)) {
            // A cost line: the function's own cost or, right after `calls=`, the inclusive cost of
            // that call; both belong to the function's inclusive cost. Trailing zero events may
            // be left out.
            let ir = line.split_whitespace().nth(self.positions.unwrap_or(1) + self.ir_index).unwrap_or("0");
            let ir: u64 = ir.parse().with_context(|| format!("bad cost line: {line}"))?;
            let name = Path::new(&self.object).file_name().map_or_else(String::new, |n| n.to_string_lossy().into());
            *self.entry_points.entry(name).or_default() += ir;
        }
        Ok(())
    }
}

/// A possibly compressed name: `(id) name` defines `id`, `(id)` refers to it, `name` is plain.
fn expand(table: &mut HashMap<String, String>, spec: &str) -> Result<String> {
    let spec = spec.trim();
    let Some(rest) = spec.strip_prefix('(') else { return Ok(spec.to_string()) };
    let Some((id, name)) = rest.split_once(')') else { bail!("bad compressed name '{spec}'") };
    let name = name.trim();
    if name.is_empty() {
        table.get(id).cloned().with_context(|| format!("compressed name ({id}) used before it was defined"))
    } else {
        table.insert(id.to_string(), name.to_string());
        Ok(name.to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A compressed profile as callgrind writes it: `crane.so`'s fmi2DoStep costs 100 itself
    /// and calls `sin` in libm for 40; `fmi2GetReal` costs 7 over two lines; a helper in the same
    /// library (not an entry point) and the importer's own functions do not count.
    const PROFILE: &str = "\
# callgrind format
version: 1
positions: line
events: Ir
summary: 1000

ob=(1) /extracted/fmu-abc/binaries/linux64/crane.so
fl=(1) ???
fn=(1) fmi2DoStep
0 100
cob=(2) /usr/lib/x86_64-linux-gnu/libm.so.6
cfi=(2) ???
cfn=(2) sin
calls=2 0
0 40
fn=(3) helper
0 500
fn=(4) fmi2GetReal
+1 3
-1 4
ob=(3) /usr/bin/crane-cosim
fn=(5) main
0 300
cob=(1)
cfn=(1)
calls=1 0
0 140
ob=(1)
fn=(1)
*2 6

totals: 1000
";

    #[test]
    fn inclusive_costs_of_the_entry_points_are_summed_per_library() {
        let profile = parse(PROFILE).unwrap();
        assert_eq!(profile.total, 1000);
        // 100 + 40 (the call to sin) + 7 (fmi2GetReal) + 6 (fmi2DoStep's block seen again);
        // the helper's 500 and main's call into crane.so (140, already counted) are not added.
        assert_eq!(profile.entry_points, BTreeMap::from([("crane.so".to_string(), 153)]));
    }

    #[test]
    fn uncompressed_names_and_extra_position_columns_are_read() {
        let text =
            "positions: instr line\nevents: Dr Ir\nob=/x/imu.so\nfn=fmi2SetReal\n0x10 5 9 2\n0x14 6 1\ntotals: 0 77\n";
        let profile = parse(text).unwrap();
        // Ir is the second event after two position columns: 2, then a line without it (0).
        assert_eq!(profile.entry_points["imu.so"], 2);
        assert_eq!(profile.total, 77);
    }

    #[test]
    fn a_truncated_profile_is_an_error() {
        assert!(parse("events: Ir\nfn=(1) fmi2DoStep\n0 5\n").is_err());
        assert!(parse("events: Ir\nfn=(9)\ntotals: 1\n").is_err(), "a name used before its definition");
    }
}
