//! Records how the extension was compiled, for `_autobal.build_info()`: the benchmarks refuse to
//! compare a dev-profile extension (opt-level 1, debug assertions) with the release CLI.
//! Cargo gives a build script the profile's settings in its environment (`OPT_LEVEL`, `DEBUG`,
//! `PROFILE`: "release" or "debug", the base a custom profile inherits from).

fn main() {
    for key in ["OPT_LEVEL", "DEBUG", "PROFILE"] {
        let v = std::env::var(key).unwrap_or_else(|_| "unknown".into());
        println!("cargo:rustc-env=AUTOBAL_BUILD_{key}={v}");
    }
    println!("cargo:rerun-if-changed=build.rs");
}
