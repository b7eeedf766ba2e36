GOCAD TSurf 1
HEADER {
name:nothing
}
END
