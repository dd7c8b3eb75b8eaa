fn main() {
    for path in std::env::args().skip(1) {
        let Ok(bytes) = std::fs::read(&path) else { continue };
        let text = String::from_utf8_lossy(&bytes);
        println!("== {path}\n{:?}", botsim_core::frontend::scan::scan(&text));
    }
}
