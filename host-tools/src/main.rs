use clap::Parser;

fn main() {
    let cli = hyst::cli::Cli::parse();
    if let Err(e) = hyst::cli::run(cli) {
        eprintln!("error: {e:#}");
        std::process::exit(1);
    }
}
