GOCAD PLine 1
HEADER {
name:line
}
