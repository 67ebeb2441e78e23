//! The `autobal` binary: [`autobal_cli::main_with_args`] on the process's arguments.

fn main() {
    std::process::exit(autobal_cli::main_with_args(std::env::args_os()));
}
