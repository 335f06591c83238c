//! The wasm test runner that `cargo test --target wasm32-unknown-unknown` calls
//! (`.cargo/config.toml` points the target's `runner` here; `cargo xtask test`
//! builds it first). It is the upstream runner, built from the workspace's exact
//! wasm-bindgen version so the two can never drift apart.

fn main() {
    if let Err(err) =
        wasm_bindgen_cli::wasm_bindgen_test_runner::run_cli_with_args(std::env::args_os())
    {
        eprintln!("error: {err:?}");
        std::process::exit(1);
    }
}
