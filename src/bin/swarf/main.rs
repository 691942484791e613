//! The `swarf` command line: the same `Job → Program → G-code` path as the page. Native only
//! (the wasm build of the crate's tests compiles it to an empty program).

#[cfg(not(target_arch = "wasm32"))]
mod cli;

#[cfg(not(target_arch = "wasm32"))]
fn main() -> std::process::ExitCode {
    cli::main()
}

#[cfg(target_arch = "wasm32")]
fn main() {}
