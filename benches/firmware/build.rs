//! Puts the repository's `memory.x` (QEMU mps2-an385/an386) on the linker's path.
use std::path::PathBuf;

fn main() {
    let out = PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    let src = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../memory.x");
    std::fs::copy(&src, out.join("memory.x")).expect("copy memory.x from the repository root");
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed={}", src.display());
    println!("cargo:rerun-if-changed=build.rs");
}
