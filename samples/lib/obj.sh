# Shell helpers the samples source: small OBJ meshes written by hand.

# An axis-aligned box as an OBJ (an occluder: a fold of paper, a sheet on a board, a wall).
box() {  # box FILE x0 x1 y0 y1 z0 z1
    local f=$1 x0=$2 x1=$3 y0=$4 y1=$5 z0=$6 z1=$7
    cat > "$f" <<EOF
v $x0 $y0 $z0
v $x1 $y0 $z0
v $x1 $y1 $z0
v $x0 $y1 $z0
v $x0 $y0 $z1
v $x1 $y0 $z1
v $x1 $y1 $z1
v $x0 $y1 $z1
f 1 3 2
f 1 4 3
f 5 6 7
f 5 7 8
f 1 2 6
f 1 6 5
f 4 8 7
f 4 7 3
f 1 5 8
f 1 8 4
f 2 3 7
f 2 7 6
EOF
}
