GOCAD TSurf 1
HEADER {
name:bad
}
TFACE
VRTX 1 0 abc 0
END
