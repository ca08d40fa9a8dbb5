mod missing {
    mechdiff_scene_macros::mechdiff_scene!("scenes/no_such_scene.toml");
}

fn main() {}
