//! Compiles the variadic FMI logger callback (`src/logger.c`).

fn main() {
    println!("cargo:rerun-if-changed=src/logger.c");
    cc::Build::new().file("src/logger.c").warnings(true).extra_warnings(true).compile("crane_cosim_logger");
}
