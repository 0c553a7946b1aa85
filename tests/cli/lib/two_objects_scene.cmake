# The small scene of the farm and checkpoint tests: a clay plane and a rough metal sphere
# under a bluish sky, 40 x 23 pixels, seed 3; `spp` samples per pixel and the AOVs `aovs`
# (a TOML list's items, e.g. "albedo", "depth").
function(write_two_objects_scene path spp aovs)
  file(WRITE "${path}" "[film]
width = 40
height = 23
spp = ${spp}
seed = 3
aovs = [${aovs}]
[camera]
from = [0, 1, 4]
to = [0, 0.5, 0]
[environment]
color = [0.8, 0.9, 1.0]
[[shader]]
name = \"clay\"
type = \"lambert\"
reflectance = [0.7, 0.4, 0.3]
[[shader]]
name = \"metal\"
type = \"conductor\"
roughness = 0.3
[[object]]
shape = \"plane\"
size = 20.0
bsdf = \"clay\"
[[object]]
shape = \"sphere\"
center = [0, 0.6, 0]
radius = 0.6
bsdf = \"metal\"
")
endfunction()
