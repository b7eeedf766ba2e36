GOCAD TSurf 1
HEADER {
name:open
