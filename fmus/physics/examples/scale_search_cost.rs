//! The cost of the test-scale search ([`physics::ship::profiles::search_test_scale`]) for one
//! profile and seed: what a Monte-Carlo case (a non-default seed) pays at start-up.
//!
//! ```text
//! cargo run --release -p physics --example scale_search_cost -- 1 7
//! valgrind --tool=callgrind target/release/examples/scale_search_cost 1 7
//! ```
//!
//! Arguments: the profile (1–3, default 1) and the seed (default 7). Prints the factor and the
//! usage it reached, bit for bit, and the wall time.

use physics::platform::kinematics::PlatformGeometry;
use physics::ship::profiles::{search_test_scale, ProfileId};
use physics::ship::rao::Hull;
use std::time::Instant;

fn main() -> Result<(), String> {
    let arg = |n: usize, default: u64| -> Result<u64, String> {
        std::env::args().nth(n).map_or(Ok(default), |a| a.parse().map_err(|e| format!("argument {a:?}: {e}")))
    };
    let id = match arg(1, 1)? {
        1 => ProfileId::One,
        2 => ProfileId::Two,
        3 => ProfileId::Three,
        n => return Err(format!("profile {n}: expected 1, 2 or 3")),
    };
    let seed = arg(2, 7)?;
    let full = id.profile().full_scale(&Hull::default(), seed);
    let start = Instant::now();
    let found = search_test_scale(&full, &PlatformGeometry::default())?;
    println!(
        "profile {} seed {seed}: scale {:e} ({:#018x}), usage {:e} ({:#018x}), {:.1} ms",
        id.profile().number,
        found.scale,
        found.scale.to_bits(),
        found.usage,
        found.usage.to_bits(),
        start.elapsed().as_secs_f64() * 1e3
    );
    Ok(())
}
