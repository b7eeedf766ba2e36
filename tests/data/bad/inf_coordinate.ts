GOCAD TSurf 1
HEADER {
name:bad
}
TFACE
VRTX 1 -inf 0 0
END
