hello world
GOCAD TSurf 1
