// placeholder until cargo xtask viewer
