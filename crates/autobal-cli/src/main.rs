//! The `autobal` binary: [`autobal_cli::main_process`] on the process's arguments.

fn main() {
    std::process::exit(autobal_cli::main_process(std::env::args_os()));
}
