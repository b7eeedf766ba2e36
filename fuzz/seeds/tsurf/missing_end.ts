GOCAD TSurf 1
HEADER {
name:noend
}
# comment before the body
TFACE
VRTX 1 0 0 0
VRTX 2 10 0 0
VRTX 3 0 10 -5
TRGL 1 2 3
