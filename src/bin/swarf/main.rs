//! The `swarf` command line: the same `Job → Program → G-code` path as the page. Native only
//! (the wasm build of the crate's tests compiles it to an empty program).

#[cfg(not(target_arch = "wasm32"))]
mod cli;

#[cfg(not(target_arch = "wasm32"))]
fn main() -> std::process::ExitCode {
    // Output into a closed pipe ends the program as it ends any Unix tool, instead of a panic
    // in `println!` (Rust ignores SIGPIPE by default).
    #[cfg(unix)]
    // SAFETY: restoring the default action of one signal, before any thread starts.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    cli::main()
}

#[cfg(target_arch = "wasm32")]
fn main() {}
