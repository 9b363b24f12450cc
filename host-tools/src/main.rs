use clap::Parser;

fn main() {
    let cli = hyst::cli::Cli::parse();
    if let Err(e) = hyst::cli::run(cli) {
        // A closed pipe (`hyst simulate ... | head`) is not an error.
        let broken_pipe = e.chain().any(|c| {
            c.downcast_ref::<std::io::Error>()
                .is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe)
        });
        if broken_pipe {
            std::process::exit(0);
        }
        eprintln!("error: {e:#}");
        std::process::exit(1);
    }
}
