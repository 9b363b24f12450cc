//! Writes the sample report (`gallery.html`) and one SVG per plot kind into
//! a folder: `cargo run -p hysteresis-host --example report_gallery -- DIR`.

#[path = "../tests/support/gallery.rs"]
mod gallery;

use std::path::PathBuf;

fn main() -> std::io::Result<()> {
    let dir = PathBuf::from(std::env::args().nth(1).unwrap_or_else(|| "gallery".into()));
    std::fs::create_dir_all(&dir)?;
    for (id, fig, _) in gallery::figures() {
        std::fs::write(dir.join(format!("{id}.svg")), fig.to_svg())?;
    }
    let page = dir.join("gallery.html");
    gallery::report().write(&page)?;
    println!("wrote {}", page.display());
    Ok(())
}
